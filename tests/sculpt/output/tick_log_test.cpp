// Tick logs: nearest-rank percentiles of tick times and the CSV rows.
#include <catch2/catch.hpp>
#include <random>

#include "argil/sculpt/output/tick_log.hpp"

namespace argil::sculpt {
namespace {

TEST_CASE("timing percentiles are nearest-rank order statistics", "[timing]") {
  // 1, 2, ..., 1000 microseconds, shuffled: the q-quantile is ceil(q n) us.
  std::vector<double> d;
  for (int k = 1; k <= 1000; ++k) d.push_back(k * 1e-6);
  std::shuffle(d.begin(), d.end(), std::mt19937(3));
  const TimingSummary s = summarize_timing(d, 2000.0);  // budget 500 us
  CHECK(s.ticks == 1000);
  CHECK(s.p50 == Approx(500e-6));
  CHECK(s.p99 == Approx(990e-6));
  CHECK(s.p999 == Approx(999e-6));
  CHECK(s.max == Approx(1000e-6));
  CHECK(s.mean == Approx(500.5e-6));
  CHECK(s.budget == Approx(500e-6));
  CHECK(s.over_budget == 500);  // 501 .. 1000 us
  const TimingSummary one = summarize_timing({7e-6}, 1000.0);
  CHECK(one.p50 == 7e-6);
  CHECK(one.p999 == 7e-6);
  CHECK(summarize_timing({}, 1000.0).ticks == 0);
}

TEST_CASE("force and contact logs hold one row per tick and per contact", "[timing]") {
  TickLog log;
  TickReport a;
  a.tick = 0;
  a.force = Eigen::Vector3d(3, 0, 4);
  TickReport b;
  b.tick = 1;
  b.time = 0.001;
  b.clamped = true;
  ContactRecord c;
  c.model = 1;
  c.face = 7;
  c.depth = 0.25;
  b.contacts = {c, c};
  log.add(a);
  log.add(b);
  const std::string forces = log.forces_csv();
  CHECK(forces.rfind("tick,time,fx,fy,fz,f,clamped,", 0) == 0);
  CHECK(forces.find("\n0,0,3,0,4,5,0,") != std::string::npos);  // |f| = 5
  CHECK(forces.find("\n1,0.001,0,0,0,0,1,") != std::string::npos);
  const std::string contacts = log.contacts_csv({"hood", "frame"});
  CHECK(std::count(contacts.begin(), contacts.end(), '\n') == 3);
  CHECK(contacts.find("\n1,0.001,frame,7,") != std::string::npos);
}

}  // namespace
}  // namespace argil::sculpt

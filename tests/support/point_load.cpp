#include "support/point_load.hpp"

#include <vector>

#include "argil/core/collision/contact.hpp"
#include "argil/core/deform/contact_response.hpp"

namespace argil::test {

Eigen::VectorXd pattern_at(const BSplineSurface& s, double a, double b) {
  std::vector<Contact> c(1);
  c[0].uv_a = {s.domain_start(Direction::u) +
                   a * (s.domain_end(Direction::u) - s.domain_start(Direction::u)),
               s.domain_start(Direction::v) +
                   b * (s.domain_end(Direction::v) - s.domain_start(Direction::v))};
  return contact_load_pattern(s, c, {1.0});
}

}  // namespace argil::test

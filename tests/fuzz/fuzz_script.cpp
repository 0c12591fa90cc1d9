// libFuzzer target: arbitrary bytes through the script loaders (JSON when the
// first byte is even, CSV otherwise). Rejection must carry a message; an
// accepted script must validate, write and read back bit for bit through
// both formats, and sample without NaN at a few rates.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "argil/sculpt/script/script.hpp"

namespace {

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "argil fuzz check failed: %s\n", what);
  std::abort();
}

bool same(const argil::sculpt::Script& a, const argil::sculpt::Script& b) {
  if (a.tool != b.tool || a.keyframes.size() != b.keyframes.size()) return false;
  for (std::size_t k = 0; k < a.keyframes.size(); ++k) {
    const auto& x = a.keyframes[k];
    const auto& y = b.keyframes[k];
    if (x.t != y.t || x.X_WD.p != y.X_WD.p || x.event != y.event ||
        x.X_WD.R.coeffs() != y.X_WD.R.coeffs())
      return false;
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const bool json = data[0] % 2 == 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  const auto script = json ? argil::sculpt::parse_script_json(text, "<fuzz>")
                           : argil::sculpt::parse_script_csv(text, "<fuzz>");
  if (!script.ok()) {
    if (script.status().message.empty()) fail("script rejection without a message");
    return 0;
  }
  const argil::sculpt::Script& s = script.value();
  if (!argil::sculpt::validate(s).ok()) fail("accepted script does not validate");
  const auto from_json =
      argil::sculpt::parse_script_json(argil::sculpt::script_to_json(s), "<json>");
  if (!from_json.ok() || !same(from_json.value(), s)) fail("JSON round trip changed the script");
  const auto from_csv = argil::sculpt::parse_script_csv(argil::sculpt::script_to_csv(s), "<csv>");
  if (!from_csv.ok() || !same(from_csv.value(), s)) fail("CSV round trip changed the script");
  // Sampling: only for scripts short enough to sample (the CLI refuses longer ones).
  if (s.keyframes.back().t <= 10.0) {
    const argil::sculpt::ScriptSampler sampler(s, 1000.0);
    for (long long k = 0; k < sampler.tick_count(); k += 1 + sampler.tick_count() / 64) {
      const auto sample = sampler.sample(k);
      if (!sample.X_WD.p.allFinite() || !sample.X_WD.R.coeffs().allFinite())
        fail("sampling gave a non-finite pose");
    }
  }
  return 0;
}

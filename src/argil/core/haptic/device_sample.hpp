#pragma once
// The input of one haptic tick: where the device handle is and whether the
// tool acts. A script sampler and a live device deliver the same stream.

#include "argil/core/geometry/pose.hpp"

namespace argil {

/// One device sample: the pose X_WD of the device handle D in the world W
/// [mm] at tick `tick` (time t = tick / rate [s]). The tool frame T is rigidly
/// attached to D and coincides with it; the proxy X_WT (ProxyState) is where
/// the tool actually is. Disengaged: the proxy follows the device and touches
/// nothing.
struct DeviceSample {
  long long tick = 0;
  double t = 0.0;  // [s]
  Pose X_WD;
  bool engaged = false;
};

}  // namespace argil

// Where the `trajectory` observer writes (H5MD particles group "bodies"), shared with the
// frame reader so both agree on one layout. Header-only constants: the plugin includes it without
// linking anything beyond the public API.
#pragma once

namespace fldsim::trajectory {

inline constexpr const char* kGroup = "/particles/bodies";
inline constexpr const char* kBox = "/particles/bodies/box";
inline constexpr const char* kBoxEdges = "/particles/bodies/box/edges";
inline constexpr const char* kPosition = "/particles/bodies/position";
inline constexpr const char* kOrientation = "/particles/bodies/orientation";
inline constexpr const char* kOffset = "/particles/bodies/lees_edwards/offset";
inline constexpr const char* kStrain = "/particles/bodies/lees_edwards/strain";

}  // namespace fldsim::trajectory

// Where the `trajectory` observer writes in the result file (an H5MD 1.1 particles group
// "bodies"): the file-format contract between that plugin, the core's frame reader
// (`system.init: {method: file}`) and readers outside fldsim (tools, `fldsim export`).
// Header-only constants.
#pragma once

namespace fldsim::trajectory {

inline constexpr const char* kGroup = "/particles/bodies";
inline constexpr const char* kBox = "/particles/bodies/box";
// [frames][3][3]: rows are the periodic cell's edge vectors a = (L, 0, 0), b = (s, L, 0),
// c = (0, 0, L); s is the Lees-Edwards image shift reduced to [-L/2, L/2) (the same lattice of
// images as the orthorhombic box with shifted images above and below). Files written before
// this layout hold [frames][3] edge lengths.
inline constexpr const char* kBoxEdges = "/particles/bodies/box/edges";
inline constexpr const char* kPosition = "/particles/bodies/position";
inline constexpr const char* kOrientation = "/particles/bodies/orientation";
// Continuous x shift of the image above, strain * L (not wrapped), and the unwrapped strain.
inline constexpr const char* kOffset = "/particles/bodies/lees_edwards/offset";
inline constexpr const char* kStrain = "/particles/bodies/lees_edwards/strain";
// The body shape in the body frame (fixed): node centres [m][3] and radii [m].
inline constexpr const char* kShapeNodes = "/particles/bodies/shape/node_positions";
inline constexpr const char* kShapeRadii = "/particles/bodies/shape/node_radii";

}  // namespace fldsim::trajectory

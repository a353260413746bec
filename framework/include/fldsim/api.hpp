// fldsim plugin ABI: the plain descriptor every plugin exports and the version it is checked
// against. The loader reads the descriptor *before* any C++ type crosses the library boundary,
// so a plugin built against another API (or another compiler/Eigen configuration) is refused
// with a message instead of crashing.
#pragma once

#include <Eigen/Core>  // for its version and alignment in the build tag
#include <cstdint>

// Major: any change to a class a plugin derives from or receives (2: Observer save/restore_state;
// 3: ForceLaw::add's virial is the molecular (body-centre) virial, no longer node-node;
// 4: HydroModel::provides_stresslets, no zero default for stresslet_sum; BlockPCG keeps its
// preconditioners out of the public header; 5: HydroModel::save_state/restore_state, so a model
// may carry state such as a preconditioner across steps and a resumed run still continues bit for
// bit; 6: RandomStream may stand for a NormalCombination of stages, which its inline normal2()
// must honour, so a plugin built with the old header would draw the wrong noise in adaptive steps).
// Minor: additions a plugin built against an older minor can ignore (fldsim::PairEnergy, the
// optional pair energy of a force law, came in 2.1 as a class of its own; fldsim::RunNotes, lines
// a component puts in the run log, in 5.3; BlockSparseMatrix::copy_from in 5.4; BlockPCG::bind in
// 5.5; parallel_loop.hpp in 5.6; BlockSparseMatrix::copy_pattern_from and set_pattern_for_overwrite in 5.7;
// BlockPCG::set_shifts and shift, IC(0) retried with a diagonal shift before falling back, in 5.8;
// RowOrder and BlockPCG::set_row_order, IC(0)'s rows graded by stiffness, in 5.9).
#define FLDSIM_API_MAJOR 6
#define FLDSIM_API_MINOR 0

#define FLDSIM_STR2(x) #x
#define FLDSIM_STR(x) FLDSIM_STR2(x)

// Everything that changes the layout of a C++ object shared with a plugin: compiler ABI,
// libstdc++ string ABI, Eigen version and alignment. Plugins and core must agree exactly.
#define FLDSIM_BUILD_TAG \
  "gcc-abi" FLDSIM_STR(__GXX_ABI_VERSION) "/cxx11abi" FLDSIM_STR(_GLIBCXX_USE_CXX11_ABI) "/eigen" FLDSIM_STR( \
      EIGEN_WORLD_VERSION) "." FLDSIM_STR(EIGEN_MAJOR_VERSION) "." FLDSIM_STR(EIGEN_MINOR_VERSION) "/align" \
      FLDSIM_STR(EIGEN_MAX_ALIGN_BYTES) "/api" FLDSIM_STR(FLDSIM_API_MAJOR)

#if defined(__GNUC__)
#define FLDSIM_VISIBLE __attribute__((visibility("default")))
#else
#define FLDSIM_VISIBLE
#endif

extern "C" {
// Plain-data descriptor exported by every plugin library under the symbol name
// `fldsim_plugin_descriptor`. Only C types: it can be read safely from any library.
struct fldsim_plugin_descriptor_t {
  std::uint32_t api_major;
  std::uint32_t api_minor;
  const char* kind;       // "shape", "hydro", "force" or "observer"
  const char* name;       // the name used in the YAML `plugin:` key
  const char* version;    // the plugin's own version, e.g. "1.0.0"
  const char* summary;    // one line for `fldsim plugins`
  const char* build_tag;  // FLDSIM_BUILD_TAG at the plugin's compile time
};
}

// What a plugin source file includes to register itself. One plugin per library:
//
//   class MyForce : public fldsim::ForceLaw {
//    public:
//     static void describe(fldsim::ParamSchema& s) { s.number("strength", 1.0, "kT", "..."); }
//     explicit MyForce(const fldsim::Params& p);
//     ...
//   };
//   FLDSIM_PLUGIN(force, MyForce, "my_force", "1.0.0", "one line for `fldsim plugins`")
//
// exports three symbols: the plain descriptor (read first, before any C++ crosses), the
// parameter schema and the factory (Boost.DLL aliases).
#pragma once

#include <boost/dll/alias.hpp>

#include "fldsim/api.hpp"
#include "fldsim/params.hpp"
#include "fldsim/plugin_base.hpp"

namespace fldsim {
using PluginDescribeFn = void(ParamSchema&);
using PluginCreateFn = Component*(const Params&);
}  // namespace fldsim

#define FLDSIM_PLUGIN(KIND, CLASS, NAME, VERSION, SUMMARY)                                           \
  extern "C" BOOST_SYMBOL_EXPORT const fldsim_plugin_descriptor_t fldsim_plugin_descriptor = {         \
      FLDSIM_API_MAJOR, FLDSIM_API_MINOR, #KIND, NAME, VERSION, SUMMARY, FLDSIM_BUILD_TAG};            \
  namespace fldsim_plugin_entry {                                                                    \
  void describe(::fldsim::ParamSchema& schema) { CLASS::describe(schema); }                          \
  ::fldsim::Component* create(const ::fldsim::Params& params) { return new CLASS(params); }           \
  }                                                                                                  \
  BOOST_DLL_ALIAS(fldsim_plugin_entry::describe, fldsim_describe)                                    \
  BOOST_DLL_ALIAS(fldsim_plugin_entry::create, fldsim_create)

#include "plugins/PluginBoundary.hpp"

#include <cxxabi.h>

#include <boost/core/demangle.hpp>
#include <exception>
#include <typeinfo>

namespace fldsim {

void rethrow_from_plugin(const std::string& who, const char* call) {
  // Every message is copied into a core-made exception before the plugin's is released.
  std::string message;
  bool config = false;
  try {
    throw;
  } catch (const ConfigError& e) {
    message = e.what();
    config = true;
  } catch (const Error& e) {
    message = who + ": " + e.what();
  } catch (const std::exception& e) {
    message = who + ": " + call + " threw " + boost::core::demangle(typeid(e).name()) + ": " + e.what();
  } catch (...) {
    const std::type_info* type = abi::__cxa_current_exception_type();
    message = who + ": " + call + " threw an exception of type " +
              (type ? boost::core::demangle(type->name()) : std::string("unknown"));
  }
  if (config) throw ConfigError(message);
  throw Error(message);
}

}  // namespace fldsim

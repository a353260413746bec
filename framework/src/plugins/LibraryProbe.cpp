#include "plugins/LibraryProbe.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <boost/dll/shared_library.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <typeinfo>

#include "fldsim/api.hpp"
#include "fldsim/plugin.hpp"
#include "plugins/SchemaWire.hpp"

namespace fldsim {

namespace {

const char* const kKinds[] = {"shape", "hydro", "force", "observer"};

std::string api_text(unsigned major, unsigned minor) {
  return std::to_string(major) + "." + std::to_string(minor);
}

// The probe itself, run in the child: everything that executes the library's code.
ProbeResult probe_here(const std::string& file) {
  ProbeResult r;
  boost::dll::shared_library library;
  std::error_code ec;
  library.load(file, boost::dll::load_mode::rtld_now, ec);
  if (ec) {
    // Boost.DLL leaves the loader's own explanation (e.g. "undefined symbol: ...") in dlerror().
    const char* why = dlerror();
    r.problem = std::string("cannot load: ") + (why ? why : ec.message());
    return r;
  }
  if (!library.has("fldsim_plugin_descriptor")) {
    r.problem = "not an fldsim plugin (no fldsim_plugin_descriptor)";
    return r;
  }
  const auto& d = library.get<const fldsim_plugin_descriptor_t>("fldsim_plugin_descriptor");
  if (d.api_major == FLDSIM_API_MAJOR) {  // only then is the layout known to hold these strings
    r.kind = d.kind ? d.kind : "";
    r.name = d.name ? d.name : "";
    r.version = d.version ? d.version : "";
    r.summary = d.summary ? d.summary : "";
  }
  if (std::string problem = descriptor_problem(d); !problem.empty()) {
    r.problem = std::move(problem);
    return r;
  }
  if (!library.has("fldsim_describe") || !library.has("fldsim_create")) {
    r.problem =
        "has a descriptor but no fldsim_describe/fldsim_create entry points (not built with FLDSIM_PLUGIN)";
    return r;
  }
  try {
    library.get_alias<PluginDescribeFn>("fldsim_describe")(r.schema);
  } catch (const std::exception& e) {
    r.problem = std::string("describe() failed: ") + e.what();
    return r;
  } catch (...) {
    r.problem = "describe() threw an exception of unknown type";
    return r;
  }
  r.usable = true;
  return r;
}

std::string encode(const ProbeResult& r) {
  WireWriter w;
  w.u64(r.usable ? 1 : 0);
  w.text(r.kind);
  w.text(r.name);
  w.text(r.version);
  w.text(r.summary);
  w.text(r.problem);
  w.schema(r.schema);
  return w.bytes();
}

ProbeResult decode(const std::string& bytes) {
  WireReader in(bytes);
  ProbeResult r;
  r.usable = in.u64() != 0;
  r.kind = in.text();
  r.name = in.text();
  r.version = in.text();
  r.summary = in.text();
  r.problem = in.text();
  r.schema = in.schema();
  return r;
}

void write_all(int fd, const std::string& bytes) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += std::size_t(n);
  }
}

// The most telling line of what the library printed: a sanitizer's or the C++ runtime's
// "ERROR"/"terminate" line if there is one, else the first line.
std::string telling_line(const std::string& text) {
  std::string first, best;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    start = end + 1;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (first.empty()) first = line;
    if (best.empty() &&
        (line.find("ERROR") != std::string::npos || line.find("terminate") != std::string::npos))
      best = line;
  }
  std::string out = best.empty() ? first : best;
  if (out.size() > 200) out = out.substr(0, 200) + "...";
  return out;
}

struct Pipe {
  int fd[2] = {-1, -1};
  bool open() { return ::pipe2(fd, O_CLOEXEC) == 0; }
  ~Pipe() {
    for (int f : fd)
      if (f >= 0) ::close(f);
  }
  void close_end(int i) {
    if (fd[i] >= 0) ::close(fd[i]);
    fd[i] = -1;
  }
};

}  // namespace

std::string descriptor_problem(const fldsim_plugin_descriptor_t& d) {
  if (d.api_major != FLDSIM_API_MAJOR || d.api_minor > FLDSIM_API_MINOR)
    return "plugin API " + api_text(d.api_major, d.api_minor) + " does not match this fldsim (API " +
           api_text(FLDSIM_API_MAJOR, FLDSIM_API_MINOR) + "); rebuild the plugin against this fldsim";
  if (!d.kind || !d.name || !d.version || !d.summary || !d.build_tag)
    return "malformed fldsim_plugin_descriptor (a null string)";
  if (std::strcmp(d.build_tag, FLDSIM_BUILD_TAG) != 0)
    return std::string("plugin build tag '") + d.build_tag + "' does not match this fldsim's '" +
           FLDSIM_BUILD_TAG + "'; rebuild the plugin against this fldsim with the same compiler";
  bool known = false;
  for (const char* k : kKinds) known = known || std::strcmp(k, d.kind) == 0;
  if (!known)
    return std::string("unknown plugin kind '") + d.kind + "' (expected shape, hydro, force or observer)";
  return "";
}

std::chrono::milliseconds probe_timeout() {
  if (const char* env = std::getenv("FLDSIM_PLUGIN_LOAD_TIMEOUT")) {
    char* end = nullptr;
    const double s = std::strtod(env, &end);
    if (end != env && *end == '\0' && std::isfinite(s) && s > 0 && s < 1e6)
      return std::chrono::milliseconds(static_cast<long>(s * 1000.0));
  }
  return std::chrono::seconds(20);
}

namespace {

// One child at work: its pipes, what it said so far, its deadline.
struct Child {
  std::size_t index = 0;
  pid_t pid = -1;
  int reply_fd = -1, output_fd = -1;
  std::string reply, printed;
  std::chrono::steady_clock::time_point deadline;
  bool timed_out = false;
};

bool start_child(const std::string& file, std::size_t index, std::chrono::milliseconds timeout, Child& child,
                 ProbeResult& failed) {
  Pipe reply, output;
  if (!reply.open() || !output.open()) {
    failed.problem = std::string("cannot probe: pipe: ") + std::strerror(errno);
    return false;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    failed.problem = std::string("cannot probe: fork: ") + std::strerror(errno);
    return false;
  }
  if (pid == 0) {
    // Child: whatever the library prints goes to the parent; exit without running any
    // destructor or atexit handler (the library's included).
    ::dup2(output.fd[1], STDOUT_FILENO);
    ::dup2(output.fd[1], STDERR_FILENO);
    write_all(reply.fd[1], encode(probe_here(file)));
    ::_exit(0);
  }
  child.index = index;
  child.pid = pid;
  child.reply_fd = reply.fd[0];
  child.output_fd = output.fd[0];
  reply.fd[0] = output.fd[0] = -1;  // now the child record's
  child.deadline = std::chrono::steady_clock::now() + timeout;
  return true;
}

ProbeResult finish_child(Child& c, std::chrono::milliseconds timeout) {
  if (c.reply_fd >= 0) ::close(c.reply_fd);
  if (c.output_fd >= 0) ::close(c.output_fd);
  if (c.timed_out) ::kill(c.pid, SIGKILL);
  int status = 0;
  while (::waitpid(c.pid, &status, 0) < 0 && errno == EINTR) {
  }
  ProbeResult failed;
  failed.died = true;
  const std::string said = telling_line(c.printed);
  const std::string suffix = said.empty() ? "" : " (it printed: " + said + ")";
  if (c.timed_out) {
    std::ostringstream limit;
    limit << double(timeout.count()) / 1000.0;
    failed.problem =
        "did not finish loading within " + limit.str() +
        " s (its static initialisers or describe() hang; FLDSIM_PLUGIN_LOAD_TIMEOUT sets the limit)" + suffix;
    return failed;
  }
  if (WIFSIGNALED(status)) {
    failed.problem = std::string("crashed while loading: signal ") + std::to_string(WTERMSIG(status)) + " (" +
                     ::strsignal(WTERMSIG(status)) + ") in its static initialisers or describe()" + suffix;
    return failed;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || c.reply.empty()) {
    failed.problem = "exited while loading (status " +
                     std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                     ") in its static initialisers or describe()" + suffix;
    return failed;
  }
  try {
    return decode(c.reply);
  } catch (const PluginError& e) {
    failed.problem = std::string("cannot probe: ") + e.what();
    return failed;
  }
}

}  // namespace

std::vector<ProbeResult> probe_libraries(const std::vector<std::string>& files,
                                         std::chrono::milliseconds timeout) {
  constexpr std::size_t kAtOnce = 8;  // children at work at once (each mostly waits on the loader)
  std::vector<ProbeResult> results(files.size());
  std::vector<Child> running;
  std::size_t next = 0;
  while (next < files.size() || !running.empty()) {
    while (next < files.size() && running.size() < kAtOnce) {
      Child c;
      if (start_child(files[next], next, timeout, c, results[next])) running.push_back(std::move(c));
      ++next;
    }
    std::vector<pollfd> fds;
    for (const auto& c : running) {
      fds.push_back({c.reply_fd, POLLIN, 0});
      fds.push_back({c.output_fd, POLLIN, 0});
    }
    const auto now = std::chrono::steady_clock::now();
    auto wait = std::chrono::milliseconds(1000);
    for (const auto& c : running)
      wait = std::min(wait, std::chrono::duration_cast<std::chrono::milliseconds>(c.deadline - now));
    const int n = ::poll(fds.data(), nfds_t(fds.size()), int(std::max<long>(0, wait.count())));
    if (n < 0 && errno != EINTR) break;
    for (std::size_t k = 0; k < running.size(); ++k) {
      Child& c = running[k];
      for (int which = 0; which < 2; ++which) {
        const pollfd& f = fds[2 * k + std::size_t(which)];
        int& fd = which == 0 ? c.reply_fd : c.output_fd;
        if (fd < 0 || !(f.revents & (POLLIN | POLLHUP | POLLERR))) continue;
        char buffer[4096];
        const ssize_t got = ::read(fd, buffer, sizeof buffer);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) {
          ::close(fd);
          fd = -1;
        } else if (which == 0 || c.printed.size() < 65536) {
          (which == 0 ? c.reply : c.printed).append(buffer, std::size_t(got));
        }
      }
    }
    const auto after = std::chrono::steady_clock::now();
    for (std::size_t k = running.size(); k-- > 0;) {
      Child& c = running[k];
      c.timed_out = after >= c.deadline && (c.reply_fd >= 0 || c.output_fd >= 0);
      if (c.timed_out || (c.reply_fd < 0 && c.output_fd < 0)) {
        results[c.index] = finish_child(c, timeout);
        running.erase(running.begin() + long(k));
      }
    }
  }
  return results;
}

ProbeResult probe_library(const std::string& file, std::chrono::milliseconds timeout) {
  return probe_libraries({file}, timeout).front();
}

}  // namespace fldsim

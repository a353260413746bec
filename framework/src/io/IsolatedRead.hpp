// A file fldsim did not just write (a result, a checkpoint, a start frame) may be corrupt, and
// HDF5 parses object headers in C without bounds checks on every path: the result-file fuzzer
// (tests/robustness/FuzzTest.cpp) found a heap overflow inside H5Aexists under AddressSanitizer.
// No exception can catch that, so the read is first done in a forked child: if the child dies
// (a signal, or a sanitizer's exit), the caller gets one fldsim::Error line and the process
// never touches the file's bytes itself.
#pragma once

#include <functional>
#include <string>

namespace fldsim::io {

// Run `read` in a forked child, with its output discarded. Returns normally when the child
// finished (whether `read` returned or threw: the caller then reads in-process and gets the
// same answer, or the same exception, from a parse now known not to crash). Throws
// fldsim::Error("<path>: <what> is damaged: reading it crashed the HDF5 library (...)") when
// the child died, and a similar line when it did not finish within `limit_seconds`.
void probe_read_in_child(const std::string& path, const std::string& what, const std::function<void()>& read,
                         double limit_seconds = 300.0);

// read() after probing it in a child: the readers of untrusted files are this one line.
template <class Read>
auto read_isolated(const std::string& path, const std::string& what, Read read) {
  probe_read_in_child(path, what, [&] { read(); });
  return read();
}

}  // namespace fldsim::io

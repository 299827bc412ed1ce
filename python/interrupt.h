// Long library calls that Ctrl-C interrupts.
#pragma once

#include <chrono>
#include <exception>
#include <future>
#include <memory>
#include <thread>
#include <utility>

#include <pybind11/pybind11.h>

namespace mpcal::python {

/// Runs `work` (which must own everything it uses: it may outlive the call)
/// on a thread of its own without the GIL, and checks for Python's signals
/// every 50 ms meanwhile. Ctrl-C raises KeyboardInterrupt at once; the work
/// then finishes on its thread and its result is dropped (the library has
/// no hook to stop a fit between iterations). Exceptions of `work` are
/// rethrown here.
template <typename Work>
auto Interruptible(Work work) -> decltype(work()) {
  using Result = decltype(work());
  auto task = std::make_shared<std::packaged_task<Result()>>(std::move(work));
  std::future<Result> done = task->get_future();
  std::thread([task] { (*task)(); }).detach();
  for (;;) {
    {
      const pybind11::gil_scoped_release unlocked;
      if (done.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready)
        break;
    }
    if (PyErr_CheckSignals() != 0) throw pybind11::error_already_set();
  }
  return done.get();
}

}  // namespace mpcal::python

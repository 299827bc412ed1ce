// Long library calls that Ctrl-C interrupts.
#pragma once

#include <chrono>
#include <exception>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>

#include <pybind11/pybind11.h>

namespace mpcal::python {

/// Releases, on the main thread, an object whose last user was a thread
/// without the GIL (Py_AddPendingCall needs neither the GIL nor a thread
/// state). Should the queue of pending calls be full, the reference is kept:
/// a leak, never a release without the GIL.
inline void ReleaseLater(PyObject* object) {
  Py_AddPendingCall(
      [](void* o) {
        Py_DECREF(static_cast<PyObject*>(o));
        return 0;
      },
      object);
}

/// Runs `work` (which must own everything it uses: it may outlive the call)
/// on a thread of its own without the GIL, and checks for Python's signals
/// every 50 ms meanwhile. Ctrl-C raises KeyboardInterrupt at once; the work
/// then finishes on its thread and its result is dropped (the library has
/// no hook to stop a fit between iterations). Exceptions of `work` are
/// rethrown here.
///
/// `in_use`: Python objects whose memory `work` reads in place (the
/// caller's numpy arrays). They are held until the work ends: released
/// here when it ends in the call, or from the pending calls of the main
/// thread when Ctrl-C left it running, so that the arrays outlive the
/// reading whatever the caller does with them after the interrupt.
template <typename Work>
auto Interruptible(Work work, pybind11::object in_use = {}) -> decltype(work()) {
  using Result = decltype(work());
  struct Held {
    std::mutex mutex;
    bool finished = false;     // the work has ended on its thread
    PyObject* left = nullptr;  // in_use, given to the thread by an interrupt
  };
  auto held = std::make_shared<Held>();
  auto task = std::make_shared<std::packaged_task<Result()>>(std::move(work));
  std::future<Result> done = task->get_future();
  std::thread([task, held] {
    (*task)();
    const std::lock_guard<std::mutex> lock(held->mutex);
    held->finished = true;
    if (held->left != nullptr) ReleaseLater(held->left);
  }).detach();
  for (;;) {
    {
      const pybind11::gil_scoped_release unlocked;
      if (done.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready)
        break;
    }
    if (PyErr_CheckSignals() != 0) {
      const std::lock_guard<std::mutex> lock(held->mutex);
      if (!held->finished && in_use) held->left = in_use.release().ptr();
      throw pybind11::error_already_set();
    }
  }
  return done.get();
}

}  // namespace mpcal::python

#pragma once
// A stop request (SIGINT/SIGTERM) that long loops poll: the app's signal handler
// sets an atomic flag, and the element loop (per block), Newton (per trial
// state), the contact evaluation (per pair) and the set-up loops (per patch,
// element or interface candidate) call check(), which throws Interrupted. The
// load stepper catches it, abandons the increment in progress and returns the
// last converged state (solver/load_stepping.hpp); thrown during set-up it ends
// the run before any results file is opened. Polling costs one relaxed atomic
// load, far below the work of an element block; a batch scheduler's SIGTERM is
// therefore obeyed within one block or one trial state, except inside a single
// sparse factorization, which cannot be left part-way.

#include <atomic>
#include <stdexcept>
#include <string>

namespace iga {

/// Thrown by StopRequest::check once a stop was requested: not an error, the
/// user's (or the scheduler's) request travelling up to whoever can act on it.
class Interrupted : public std::runtime_error {
public:
    Interrupted() : std::runtime_error("interrupted (SIGINT/SIGTERM)") {}
};

class StopRequest {
public:
    StopRequest() = default;  ///< never stops
    explicit StopRequest(const std::atomic<bool>* flag) : flag_(flag) {}

    bool requested() const { return flag_ != nullptr && flag_->load(std::memory_order_relaxed); }
    /// Throws Interrupted when a stop was requested.
    void check() const
    {
        if (requested())
            throw Interrupted();
    }

private:
    const std::atomic<bool>* flag_ = nullptr;
};

}  // namespace iga

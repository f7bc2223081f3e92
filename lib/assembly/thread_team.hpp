#pragma once
// ThreadTeam: n - 1 helper threads that sleep between jobs, for the colored
// block loop (SparsePattern::for_each_block). Owned by whoever runs the loop
// repeatedly (analysis::SceneSystem, one per run): no global pool.
//
// A job is offered to the helpers and run by the caller at the same time; the
// caller never waits for a helper to *arrive*, only for work a helper has
// already *claimed*. A helper that the scheduler keeps off its core (a loaded
// machine) therefore costs nothing: the caller does all the work, and the helper
// finds the job gone when it wakes. All waiting is passive (condition variables
// and std::atomic::wait, which block in the kernel after a short spin), so idle
// helpers take no CPU from other processes.

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace iga::assembly {

class ThreadTeam {
public:
    /// n_threads >= 1 counts the caller: n_threads - 1 helpers are started (fewer
    /// if the system refuses threads; n_threads() tells).
    explicit ThreadTeam(int n_threads);
    ~ThreadTeam();
    ThreadTeam(const ThreadTeam&) = delete;
    ThreadTeam& operator=(const ThreadTeam&) = delete;

    int n_threads() const { return static_cast<int>(helpers_.size()) + 1; }

    /// Calls work() on the calling thread and on every helper that picks the job
    /// up before the caller's work() returns; returns when the caller's call and
    /// every call that started have returned. work must be safe to call
    /// concurrently and must return promptly once there is nothing left to do.
    void run(const std::function<void()>& work);

private:
    void helper_loop();

    std::vector<std::thread> helpers_;
    std::mutex mutex_;
    std::condition_variable offered_;   // a new job, or stop
    std::condition_variable finished_;  // a helper left the job
    const std::function<void()>* job_ = nullptr;
    unsigned long generation_ = 0;
    int active_ = 0;  // helpers inside the current job
    bool stop_ = false;
};

}  // namespace iga::assembly

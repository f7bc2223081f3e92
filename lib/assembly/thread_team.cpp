#include "assembly/thread_team.hpp"

#include <system_error>

namespace iga::assembly {

ThreadTeam::ThreadTeam(int n_threads)
{
    for (int t = 1; t < n_threads; ++t) {
        try {
            helpers_.emplace_back([this] { helper_loop(); });
        } catch (const std::system_error&) {  // no more threads: a smaller team
            break;
        }
    }
}

ThreadTeam::~ThreadTeam()
{
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    offered_.notify_all();
    for (std::thread& t : helpers_)
        t.join();
}

void ThreadTeam::helper_loop()
{
    unsigned long seen = 0;
    for (;;) {
        const std::function<void()>* job = nullptr;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            offered_.wait(lock, [&] { return stop_ || (job_ != nullptr && generation_ != seen); });
            if (stop_)
                return;
            seen = generation_;
            job = job_;
            ++active_;
        }
        (*job)();
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            --active_;
        }
        finished_.notify_all();
    }
}

void ThreadTeam::run(const std::function<void()>& work)
{
    if (helpers_.empty()) {
        work();
        return;
    }
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        job_ = &work;
        ++generation_;
    }
    offered_.notify_all();
    work();
    std::unique_lock<std::mutex> lock(mutex_);
    job_ = nullptr;  // helpers that wake from now on skip this job
    finished_.wait(lock, [&] { return active_ == 0; });
}

}  // namespace iga::assembly

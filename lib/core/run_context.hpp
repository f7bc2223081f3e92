#pragma once
// RunContext: the log sink and the named timers of one run, passed explicitly
// (no globals). Timers accumulate wall seconds under names that become the
// attributes of /timings in the results file (total, assembly, contact_search,
// projection, linear_solve, output, ...). Counters (candidates, projections,
// ...) accumulate integers the same way. The stop request (core/stop.hpp) is
// polled by the loops that receive the context.

#include "core/stop.hpp"

#include <chrono>
#include <functional>
#include <map>
#include <string>

namespace iga {

enum class Verbosity { quiet = 0, normal = 1, verbose = 2 };

class RunContext {
public:
    using Sink = std::function<void(Verbosity level, const std::string& line)>;

    RunContext() = default;
    explicit RunContext(Sink sink, Verbosity verbosity = Verbosity::normal)
        : sink_(std::move(sink)), verbosity_(verbosity) {}

    /// Sends a line to the sink when the verbosity allows it.
    void log(Verbosity level, const std::string& line) const
    {
        if (sink_ && level <= verbosity_)
            sink_(level, line);
    }
    Verbosity verbosity() const { return verbosity_; }

    void set_stop(StopRequest stop) { stop_ = stop; }
    const StopRequest& stop() const { return stop_; }

    void add_time(const std::string& name, double seconds) { timers_[name] += seconds; }
    void add_count(const std::string& name, long long n) { counters_[name] += n; }
    const std::map<std::string, double>& timers() const { return timers_; }
    const std::map<std::string, long long>& counters() const { return counters_; }
    double time(const std::string& name) const
    {
        auto it = timers_.find(name);
        return it == timers_.end() ? 0.0 : it->second;
    }
    long long count(const std::string& name) const
    {
        auto it = counters_.find(name);
        return it == counters_.end() ? 0 : it->second;
    }

private:
    Sink sink_;
    Verbosity verbosity_ = Verbosity::normal;
    std::map<std::string, double> timers_;
    std::map<std::string, long long> counters_;
    StopRequest stop_;
};

/// Adds the wall time of its scope to a named timer of a RunContext (if any).
class ScopedTimer {
public:
    ScopedTimer(RunContext* context, std::string name)
        : context_(context), name_(std::move(name)), start_(std::chrono::steady_clock::now()) {}
    ~ScopedTimer()
    {
        if (context_)
            context_->add_time(name_, elapsed());
    }
    double elapsed() const
    {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    ScopedTimer(const ScopedTimer&) = delete;
    ScopedTimer& operator=(const ScopedTimer&) = delete;

private:
    RunContext* context_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace iga

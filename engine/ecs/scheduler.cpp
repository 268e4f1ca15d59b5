#include "scheduler.h"

#include "engine/core/error.h"

#include <algorithm>

namespace specula::ecs {

void Scheduler::add(std::string name, System fn, std::vector<std::string> after) {
    entries_.push_back({std::move(name), std::move(fn), std::move(after)});
    dirty_ = true;
}

void Scheduler::resolve() {
    // Kahn's algorithm, always taking the earliest-declared ready system.
    const std::size_t n = entries_.size();
    std::vector<std::vector<std::size_t>> next(n);
    std::vector<int> indegree(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
        for (const std::string& dep : entries_[i].after) {
            auto it = std::find_if(entries_.begin(), entries_.end(),
                                   [&](const Entry& e) { return e.name == dep; });
            if (it == entries_.end())
                throw Error("", "system '" + entries_[i].name + "'",
                            "runs after unknown system '" + dep + "'");
            next[std::size_t(it - entries_.begin())].push_back(i);
            ++indegree[i];
        }
    }
    order_.clear();
    std::vector<bool> done(n, false);
    while (order_.size() < n) {
        std::size_t pick = n;
        for (std::size_t i = 0; i < n && pick == n; ++i)
            if (!done[i] && indegree[i] == 0) pick = i;
        if (pick == n) throw Error("", "systems", "the 'after' constraints form a cycle");
        done[pick] = true;
        order_.push_back(pick);
        for (std::size_t j : next[pick])
            --indegree[j];
    }
    orderNames_.clear();
    for (std::size_t i : order_)
        orderNames_.push_back(entries_[i].name);
    dirty_ = false;
}

const std::vector<std::string>& Scheduler::order() {
    if (dirty_) resolve();
    return orderNames_;
}

void Scheduler::run(Registry& registry, const FrameContext& ctx) {
    if (dirty_) resolve();
    for (std::size_t i : order_)
        entries_[i].fn(registry, ctx);
}

} // namespace specula::ecs

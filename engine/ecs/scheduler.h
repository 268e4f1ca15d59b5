#pragma once
// Systems are free functions over the registry. The scheduler runs them in a declared
// order: each system may name systems it must run after; ties keep insertion order.
#include "registry.h"

#include <functional>
#include <string>
#include <vector>

namespace specula::ecs {

struct FrameContext {
    double time = 0.0;      // seconds since start
    double deltaTime = 0.0; // seconds since the previous frame
    std::uint64_t frame = 0;
};

using System = std::function<void(Registry&, const FrameContext&)>;

class Scheduler {
public:
    // Throws specula::Error when `after` names an unknown system or makes a cycle.
    void add(std::string name, System fn, std::vector<std::string> after = {});
    void run(Registry& registry, const FrameContext& ctx);
    const std::vector<std::string>& order(); // resolved execution order

private:
    void resolve();
    struct Entry {
        std::string name;
        System fn;
        std::vector<std::string> after;
    };
    std::vector<Entry> entries_;
    std::vector<std::size_t> order_;
    std::vector<std::string> orderNames_;
    bool dirty_ = true;
};

} // namespace specula::ecs

#pragma once
// The registry owns entities and one sparse set per component type. Components are plain
// structs; nothing here knows what they mean.
#include "entity.h"
#include "sparse_set.h"

#include <cassert>
#include <memory>
#include <tuple>
#include <typeindex>
#include <unordered_map>
#include <vector>

namespace specula::ecs {

class Registry;

// Iterates entities that have all of Ts. Walks the smallest of the pools and probes the
// others, so a view over a rare component is cheap however many entities exist.
template <typename... Ts> class View {
public:
    explicit View(std::tuple<SparseSet<Ts>*...> pools) : pools_(pools) {}

    template <typename Fn> void each(Fn&& fn) {
        if ((!std::get<SparseSet<Ts>*>(pools_) || ...)) return;
        const std::vector<Entity>* smallest = nullptr;
        std::apply(
            [&](auto*... p) {
                ((smallest =
                      (!smallest || p->size() < smallest->size()) ? &p->entities() : smallest),
                 ...);
            },
            pools_);
        // Walk backwards: removing the current entity swaps in an already-visited one, and
        // entities added during the walk land past the end, so fn may edit the registry.
        for (std::size_t i = smallest->size(); i-- > 0;) {
            if (i >= smallest->size()) continue;
            const Entity e = (*smallest)[i];
            if ((std::get<SparseSet<Ts>*>(pools_)->contains(e) && ...))
                fn(e, std::get<SparseSet<Ts>*>(pools_)->get(e)...);
        }
    }

    std::size_t count() {
        std::size_t n = 0;
        each([&](Entity, Ts&...) { ++n; });
        return n;
    }

private:
    std::tuple<SparseSet<Ts>*...> pools_;
};

class Registry {
public:
    Entity create() {
        if (!free_.empty()) {
            const std::uint32_t index = free_.back();
            free_.pop_back();
            return Entity{index, generations_[index]};
        }
        generations_.push_back(0);
        return Entity{static_cast<std::uint32_t>(generations_.size() - 1), 0};
    }

    bool valid(Entity e) const {
        // A destroyed slot's generation was bumped, so no live handle carries it until
        // create() hands the slot out again.
        return !e.isNull() && e.index < generations_.size() &&
               generations_[e.index] == e.generation;
    }

    // Destroying a stale handle is a no-op: the slot may already belong to someone else.
    void destroy(Entity e) {
        if (!valid(e)) return;
        for (auto& [type, pool] : pools_)
            pool->remove(e);
        ++generations_[e.index];
        free_.push_back(e.index);
    }

    template <typename T, typename... Args> T& emplace(Entity e, Args&&... args) {
        assert(valid(e));
        return pool<T>().emplace(e, std::forward<Args>(args)...);
    }
    template <typename T> void remove(Entity e) {
        if (auto* p = findPool<T>()) p->remove(e);
    }
    template <typename T> bool has(Entity e) const {
        const auto* p = findPool<T>();
        return p && p->contains(e);
    }
    template <typename T> T* find(Entity e) {
        auto* p = findPool<T>();
        return p ? p->find(e) : nullptr;
    }
    template <typename T> const T* find(Entity e) const {
        const auto* p = findPool<T>();
        return p ? p->find(e) : nullptr;
    }
    template <typename T> T& get(Entity e) {
        T* c = find<T>(e);
        assert(c && "entity lacks the component");
        return *c;
    }

    // The tuple is spelled out: a braced list is ambiguous with View's copy constructor when
    // there is a single component type.
    template <typename... Ts> View<Ts...> view() {
        return View<Ts...>(std::tuple<SparseSet<Ts>*...>(findPool<Ts>()...));
    }

    std::size_t alive() const { return generations_.size() - free_.size(); }

private:
    template <typename T> SparseSet<T>& pool() {
        auto& slot = pools_[std::type_index(typeid(T))];
        if (!slot) slot = std::make_unique<SparseSet<T>>();
        return static_cast<SparseSet<T>&>(*slot);
    }
    template <typename T> SparseSet<T>* findPool() const {
        auto it = pools_.find(std::type_index(typeid(T)));
        return it == pools_.end() ? nullptr : static_cast<SparseSet<T>*>(it->second.get());
    }

    std::vector<std::uint32_t> generations_;
    std::vector<std::uint32_t> free_;
    std::unordered_map<std::type_index, std::unique_ptr<SparseSetBase>> pools_;
};

} // namespace specula::ecs

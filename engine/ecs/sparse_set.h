#pragma once
// Sparse-set storage for one component type: `sparse[index]` points into the packed
// `dense` arrays, so iteration touches only live components and lookup is O(1).
// Removal swaps the last element into the hole (order is not stable).
#include "entity.h"

#include <cassert>
#include <cstdint>
#include <vector>

namespace specula::ecs {

class SparseSetBase {
public:
    virtual ~SparseSetBase() = default;
    virtual void remove(Entity e) = 0;
    virtual bool contains(Entity e) const = 0;
    virtual std::size_t size() const = 0;
    const std::vector<Entity>& entities() const { return dense_; }

protected:
    static constexpr std::uint32_t kAbsent = UINT32_MAX;
    std::vector<std::uint32_t> sparse_; // entity index -> position in dense_, or kAbsent
    std::vector<Entity> dense_;         // packed owners, same order as the components
};

template <typename T> class SparseSet final : public SparseSetBase {
public:
    template <typename... Args> T& emplace(Entity e, Args&&... args) {
        if (e.index >= sparse_.size()) sparse_.resize(e.index + 1, kAbsent);
        if (std::uint32_t at = sparse_[e.index]; at != kAbsent) {
            dense_[at] = e;
            components_[at] = T{std::forward<Args>(args)...};
            return components_[at];
        }
        sparse_[e.index] = static_cast<std::uint32_t>(dense_.size());
        dense_.push_back(e);
        components_.push_back(T{std::forward<Args>(args)...});
        return components_.back();
    }

    void remove(Entity e) override {
        if (!contains(e)) return;
        const std::uint32_t at = sparse_[e.index];
        const std::uint32_t last = static_cast<std::uint32_t>(dense_.size() - 1);
        if (at != last) {
            dense_[at] = dense_[last];
            components_[at] = std::move(components_[last]);
            sparse_[dense_[at].index] = at;
        }
        dense_.pop_back();
        components_.pop_back();
        sparse_[e.index] = kAbsent;
    }

    bool contains(Entity e) const override {
        return e.index < sparse_.size() && sparse_[e.index] != kAbsent &&
               dense_[sparse_[e.index]] == e;
    }

    std::size_t size() const override { return dense_.size(); }

    T* find(Entity e) { return contains(e) ? &components_[sparse_[e.index]] : nullptr; }
    const T* find(Entity e) const { return contains(e) ? &components_[sparse_[e.index]] : nullptr; }
    T& get(Entity e) {
        assert(contains(e));
        return components_[sparse_[e.index]];
    }
    std::vector<T>& components() { return components_; }

private:
    std::vector<T> components_;
};

} // namespace specula::ecs

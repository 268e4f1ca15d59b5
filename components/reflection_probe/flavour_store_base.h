#pragma once
// The bookkeeping every flavour's store shares, written once: one entry per probe entity
// holding the flavour's GPU state (`Probe`) and the settings it was last built from. A
// flavour implements three things: loadProbe (asset -> GPU state), applySettings (settings
// -> parameters) and drawReflector; edits are found by comparing settings here.
#include "components/reflection_probe/probe_flavour.h"

#include <memory>
#include <string>
#include <unordered_map>

namespace specula {

// The CPU copy of cooked assets, by manifest path: probes that share an asset share one copy,
// read once while any probe holds it. Each store keeps one for its flavour's asset type.
template <typename Asset> class SharedAssets {
public:
    // The asset of `manifestPath`, from `read()` when no probe holds it now.
    template <typename Read>
    std::shared_ptr<const Asset> get(const std::string& manifestPath, Read read) {
        std::weak_ptr<const Asset>& cached = cache_[manifestPath];
        std::shared_ptr<const Asset> asset = cached.lock();
        if (!asset) cached = asset = std::make_shared<const Asset>(read());
        return asset;
    }

private:
    std::unordered_map<std::string, std::weak_ptr<const Asset>> cache_;
};

template <typename Settings, typename Probe> class FlavourStoreBase : public ProbeFlavourStore {
public:
    void load(ecs::Entity e, const ProbeManifest& manifest, ProbeFrameStats& stats) final {
        Probe fresh = loadProbe(manifest, stats); // throws before anything changed
        entries_.insert_or_assign(e, Entry{std::move(fresh), Settings{}, false});
    }

    void update(const ecs::Registry& registry, ecs::Entity e, ProbeFrameStats& stats) final {
        Entry& entry = entries_.at(e);
        const Settings* found = registry.find<Settings>(e);
        const Settings settings = found ? *found : Settings{};
        if (entry.applied && entry.settings == settings) return;
        applySettings(entry.probe, settings, stats); // throws before any change
        entry.settings = settings;
        entry.applied = true;
    }

    void drop(ecs::Entity e) final { entries_.erase(e); }

    bool holdsSettings(const ecs::Registry& registry, ecs::Entity e) const final {
        return registry.has<Settings>(e);
    }

    std::size_t gpuBytes() const final {
        std::size_t bytes = 0;
        for (const auto& [e, entry] : entries_)
            bytes += gpuBytesOf(entry.probe);
        return bytes;
    }

    bool drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector,
                       const Reflector& r) final {
        const Entry* entry = find(r.probe);
        if (entry) drawReflector(ctx, reflector, r, entry->probe, entry->settings);
        return entry != nullptr;
    }

    // The GPU state of a probe whose settings applied (null otherwise).
    const Probe* probe(ecs::Entity e) const {
        const Entry* entry = find(e);
        return entry ? &entry->probe : nullptr;
    }
    const Settings* settings(ecs::Entity e) const {
        const Entry* entry = find(e);
        return entry ? &entry->settings : nullptr;
    }

protected:
    struct Entry {
        Probe probe;
        Settings settings;
        bool applied = false; // settings applied at least once: the probe can draw
    };

    virtual Probe loadProbe(const ProbeManifest& manifest, ProbeFrameStats& stats) = 0;
    virtual void applySettings(Probe& probe, const Settings& settings, ProbeFrameStats& stats) = 0;
    virtual std::size_t gpuBytesOf(const Probe& probe) const = 0;
    virtual void drawReflector(const ProbeDrawContext& ctx, ecs::Entity reflector,
                               const Reflector& r, const Probe& probe,
                               const Settings& settings) = 0;

    const Entry* find(ecs::Entity e) const {
        auto it = entries_.find(e);
        return it == entries_.end() || !it->second.applied ? nullptr : &it->second;
    }
    const std::unordered_map<ecs::Entity, Entry>& entries() const { return entries_; }

private:
    std::unordered_map<ecs::Entity, Entry> entries_;
};

} // namespace specula

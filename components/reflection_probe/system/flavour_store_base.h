#pragma once
// The bookkeeping every flavour's store shares, written once: one entry per probe entity
// holding the flavour's GPU state (`Probe`) and the settings it was last built from. A
// flavour implements three things: loadProbe (asset -> GPU state), applySettings (settings
// -> parameters) and drawReflector; edits are found by comparing settings here.
#include "components/reflection_probe/system/probe_flavour.h"
#include "engine/gpu/gl_objects.h"
#include "engine/gpu/shader.h"

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace specula {

// The texture unit every flavour's reflector shader reads uRoughnessMap from: above the units
// the flavours bind today (1..6), so a map never displaces a probe texture.
inline constexpr GLuint kRoughnessMapUnit = 7;

// Whether a reflector reads a roughness map (HAS_ROUGHNESS_MAP): a rough one (NaN or 0: a
// mirror, which reads no roughness at all) with a map. Reflectors without one compile and
// bind exactly what they did before maps existed.
inline bool usesRoughnessMap(const Reflector& r) {
    return r.roughness > 0.f && r.roughnessMap;
}

// A roughness map as reflector_roughness.glsl.h reads it: its G channel alone (rgba().g: 0
// where the image has one channel, as the twin reads it), as R32F, so the shader filters the
// very floats the CPU twin (roughnessAt: sampleBilinear of the float image) filters; R8 would
// round the map to 1/255 and the twin would no longer read what the GPU does. GL_LINEAR
// without mipmaps and GL_REPEAT on S and T, as the twin samples.
inline std::size_t roughnessMapTextureBytes(const Image& map) {
    return std::size_t(map.width) * std::size_t(map.height) * 4; // R32F
}
inline gpu::Texture roughnessMapTexture(const Image& map) {
    std::vector<float> g(std::size_t(map.width) * std::size_t(map.height));
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x)
            g[std::size_t(y) * std::size_t(map.width) + std::size_t(x)] = map.rgba(x, y).g;
    gpu::Texture texture = gpu::Texture::create(GL_TEXTURE_2D);
    const GLuint tex = texture.id();
    glTextureStorage2D(tex, 1, GL_R32F, map.width, map.height);
    glTextureSubImage2D(tex, 0, 0, 0, map.width, map.height, GL_RED, GL_FLOAT, g.data());
    for (const GLenum filter : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER})
        glTextureParameteri(tex, filter, GL_LINEAR);
    for (const GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T})
        glTextureParameteri(tex, wrap, GL_REPEAT);
    return texture;
}

// The roughness maps a store's rough reflectors read, one texture per distinct map (keyed by
// the Image: reflectors of one material share its map, and so its texture). An entry counts
// only while its image is the very one alive (a freed image's address may come back).
class RoughnessMapTextures {
public:
    // Uploads `map` unless it is held (one texture upload in `stats`).
    void prepare(const std::shared_ptr<const Image>& map, ProbeFrameStats& stats) {
        Entry& e = entries_[map.get()];
        if (e.texture && e.image.lock() == map) return;
        e = Entry{map, roughnessMapTexture(*map), roughnessMapTextureBytes(*map)};
        ++stats.textureUploads;
    }
    // Binds the map of a reflector that usesRoughnessMap (uploaded here unless it was).
    void bind(gpu::Program& prog, const Reflector& r, ProbeFrameStats& stats) {
        prepare(r.roughnessMap, stats);
        glBindTextureUnit(kRoughnessMapUnit, entries_.at(r.roughnessMap.get()).texture.id());
        prog.setUniform("uRoughnessMap", int(kRoughnessMapUnit));
    }
    // Frees the textures of maps no longer alive.
    void dropExpired() {
        std::erase_if(entries_, [](const auto& e) { return e.second.image.expired(); });
    }
    std::size_t bytes() const {
        std::size_t sum = 0;
        for (const auto& [image, e] : entries_)
            sum += e.bytes;
        return sum;
    }

private:
    struct Entry {
        std::weak_ptr<const Image> image;
        gpu::Texture texture;
        std::size_t bytes = 0; // roughnessMapTextureBytes
    };
    std::unordered_map<const Image*, Entry> entries_;
};

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

    // The probes' textures and the roughness maps their reflectors read.
    std::size_t gpuBytes() const final {
        std::size_t bytes = roughnessMaps_.bytes();
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

    // For syncReflectors: uploads the roughness map of every rough reflector of this store's
    // probes that has one, so that the timed reflector pass only binds.
    void syncRoughnessMaps(ecs::Registry& registry, ProbeFrameStats& stats) {
        roughnessMaps_.dropExpired();
        registry.view<Reflector>().each([&](ecs::Entity, Reflector& r) {
            if (usesRoughnessMap(r) && find(r.probe)) roughnessMaps_.prepare(r.roughnessMap, stats);
        });
    }
    RoughnessMapTextures roughnessMaps_;

private:
    std::unordered_map<ecs::Entity, Entry> entries_;
};

} // namespace specula

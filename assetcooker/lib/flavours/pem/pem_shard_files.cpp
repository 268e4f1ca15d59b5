#include "assetcooker/lib/flavours/pem/pem_shard_files.h"

#include "assetcooker/lib/os/binary_file.h"
#include "engine/core/error.h"
#include "engine/core/file_write.h"

#include <cstring>
#include <filesystem>
#include <fstream>

namespace specula {

namespace {

constexpr char kTraceMagic[8] = {'S', 'P', 'P', 'E', 'M', 'T', 'R', 'C'};
constexpr char kMapMagic[8] = {'S', 'P', 'P', 'E', 'M', 'M', 'A', 'P'};
// 2: PemSample::pixel and centre.
constexpr std::uint32_t kVersion = 3; // 3: a sample map may be left out

// Every member of a PemSample, in file order. The structured binding names them all: a
// member added to PemSample stops this from compiling until it is listed here.
template <class S, class F> void pemSampleFields(S& s, F&& f) {
    auto& [x, l, target, distant, selfHit, onHull, dxdX, dxdY, dldX, dldY, pixel, centre] = s;
    f("x", x), f("l", l), f("target", target), f("distant", distant);
    f("self_hit", selfHit), f("on_hull", onHull);
    f("dxdX", dxdX), f("dxdY", dxdY), f("dldX", dldX), f("dldY", dldY), f("pixel", pixel);
    f("centre", centre);
}

// Every member of a PemMap, in file order (the distance cube as a flag: it is the asset's).
template <class M, class F> void pemMapFields(M& m, F&& f) {
    auto& [faceRes, boxMin, boxMax, texels, distance, local, alpha, levels] = m;
    f("face_res", faceRes), f("box_min", boxMin), f("box_max", boxMax), f("texels", texels);
    f("distance", distance), f("local", local), f("alpha", alpha), f("levels", levels);
}

// Writes one value of any member type above.
struct Put {
    std::string& out;
    void operator()(const char*, float v) const { binary::put(out, v); }
    void operator()(const char*, int v) const { binary::put(out, std::int32_t(v)); }
    void operator()(const char*, bool v) const { binary::put(out, std::uint8_t(v ? 1 : 0)); }
    void operator()(const char* n, const glm::vec3& v) const {
        (*this)(n, v.x), (*this)(n, v.y), (*this)(n, v.z);
    }
    template <class T> void operator()(const char* n, const std::vector<T>& v) const {
        binary::put(out, std::uint64_t(v.size()));
        for (const T& x : v)
            (*this)(n, x);
    }
    void operator()(const char* n, const std::optional<PemLocalSphere>& s) const {
        (*this)(n, s.has_value());
        if (s) (*this)(n, s->centre), (*this)(n, s->radius);
    }
    void operator()(const char* n, const std::shared_ptr<const PemDistanceGeometry>& d) const {
        (*this)(n, d != nullptr);
    }
};

// Reads one value of any member type above; `distance` is what a set flag points to.
struct Get {
    binary::Reader& in;
    const std::string& file;
    std::string prefix;
    std::shared_ptr<const PemDistanceGeometry> distance;

    std::string field(const char* n) const { return prefix + n; }
    void operator()(const char* n, float& v) const { v = in.get<float>(field(n)); }
    void operator()(const char* n, int& v) const { v = in.get<std::int32_t>(field(n)); }
    void operator()(const char* n, bool& v) const {
        const std::uint8_t b = in.get<std::uint8_t>(field(n));
        if (b > 1) throw Error(file, field(n), "expected a flag 0 or 1, got " + std::to_string(b));
        v = b == 1;
    }
    void operator()(const char* n, glm::vec3& v) const {
        (*this)(n, v.x), (*this)(n, v.y), (*this)(n, v.z);
    }
    template <class T> void operator()(const char* n, std::vector<T>& v) const {
        const std::uint64_t count = in.get<std::uint64_t>(field(n));
        // Each element takes at least one byte: a count past the bytes left is a lie.
        if (count > in.left())
            throw Error(file, field(n),
                        "count " + std::to_string(count) + " past the file's " +
                            std::to_string(in.left()) + " bytes left");
        v.resize(std::size_t(count));
        for (T& x : v)
            (*this)(n, x);
    }
    void operator()(const char* n, std::optional<PemLocalSphere>& s) const {
        bool has = false;
        (*this)(n, has);
        s.reset();
        if (!has) return;
        s.emplace();
        (*this)(n, s->centre), (*this)(n, s->radius);
    }
    void operator()(const char* n, std::shared_ptr<const PemDistanceGeometry>& d) const {
        bool has = false;
        (*this)(n, has);
        if (has && !distance)
            throw Error(file, field(n), "a map of distance geometry in a bake of box geometry");
        d = has ? distance : nullptr;
    }
    void operator()(const char* n, PemSample& s) const {
        pemSampleFields(s, *this);
        (void)n;
    }
};

std::string header(const char (&magic)[8]) {
    std::string out(magic, sizeof magic);
    binary::put(out, kVersion);
    return out;
}

void checkHeader(binary::Reader& in, const std::string& file, const char (&magic)[8],
                 const char* what) {
    in.need(sizeof magic, "magic");
    if (std::memcmp(in.here(), magic, sizeof magic) != 0)
        throw Error(file, "magic",
                    std::string("expected a specula ") + what + " file (" +
                        std::string(magic, sizeof magic) + ")");
    in.skip(sizeof magic);
    const std::uint32_t version = in.get<std::uint32_t>("version");
    if (version != kVersion)
        throw Error(file, "version",
                    "expected " + std::to_string(kVersion) + ", got " + std::to_string(version));
}

void checkEnd(const binary::Reader& in, const std::string& file) {
    if (in.left() != 0)
        throw Error(file, "", std::to_string(in.left()) + " bytes past the end of the data");
}

} // namespace

void writePemTrace(const PemSamples& samples, const std::string& file) {
    std::string out = header(kTraceMagic);
    const Put put{out};
    // The decision's inputs first: a sample shard reads only this part of the other traces.
    const PemDecisionInputs in = pemDecisionInputs(samples);
    // Grown once: a trace is megabytes, written a few bytes at a time.
    out.reserve(out.size() + 32 + in.offHull.size() * sizeof(glm::vec3) +
                samples.size() * sizeof(PemSample));
    put("self_hits", in.selfHits), put("off_hull", in.offHull);
    binary::put(out, std::uint64_t(samples.size()));
    for (const PemSample& s : samples)
        pemSampleFields(s, put);
    writeFileAtomically(file, out);
}

namespace {

PemDecisionInputs readDecisionInputs(binary::Reader& in, const std::string& file) {
    checkHeader(in, file, kTraceMagic, "PEM trace");
    PemDecisionInputs inputs;
    const Get get{in, file, "", nullptr};
    get("self_hits", inputs.selfHits), get("off_hull", inputs.offHull);
    return inputs;
}

// Up to n bytes from f into `to` (a read may return fewer than asked before the end).
std::size_t readUpTo(RegularFile& f, char* to, std::size_t n) {
    std::size_t done = 0;
    while (done < n)
        if (const std::size_t got = f.read(to + done, n - done); got > 0)
            done += got;
        else
            break;
    return done;
}

} // namespace

PemDecisionInputs readPemTraceDecisionInputs(const std::string& file) {
    RegularFile f(file, binary::kMaxShardFileBytes);
    // The header and the off-hull count, then exactly the points: not the samples after them.
    std::string bytes(sizeof kTraceMagic + 4 + 1 + 8, '\0');
    bytes.resize(readUpTo(f, bytes.data(), bytes.size()));
    std::uint64_t count = 0;
    {
        binary::Reader head(file, bytes);
        checkHeader(head, file, kTraceMagic, "PEM trace");
        head.get<std::uint8_t>("self_hits");
        count = head.get<std::uint64_t>("off_hull");
    }
    const std::uint64_t size = f.size();
    if (count > size / 12)
        throw Error(file, "off_hull",
                    "count " + std::to_string(count) + " past the file's " + std::to_string(size) +
                        " bytes");
    const std::size_t head = bytes.size();
    bytes.resize(head + std::size_t(count) * 12);
    bytes.resize(head + readUpTo(f, bytes.data() + head, std::size_t(count) * 12));
    binary::Reader in(file, bytes);
    return readDecisionInputs(in, file);
}

PemSamples readPemTrace(const std::string& file) {
    const std::string bytes = binary::readAll(file);
    binary::Reader in(file, bytes);
    const PemDecisionInputs inputs = readDecisionInputs(in, file);
    PemSamples samples;
    const Get get{in, file, "samples.", nullptr};
    get("samples", samples);
    checkEnd(in, file);
    // The two parts of one trace agree: a file pieced together from two is refused.
    const PemDecisionInputs again = pemDecisionInputs(samples);
    if (again.selfHits != inputs.selfHits || again.offHull != inputs.offHull)
        throw Error(file, "off_hull", "does not match the samples after it");
    return samples;
}

void writePemSampleShard(const PemSampleShard& shard, const std::string& file) {
    std::string out = header(kMapMagic);
    const Put put{out};
    put("sample", shard.sample);
    put("left_out", shard.leftOut);
    const PemLocalDecision& d = shard.decision;
    put("local", d.local), put("local_face_res", d.faceRes);
    put("sphere", d.sphere.centre), put("sphere", d.sphere.radius);
    pemMapFields(shard.map.map, put);
    pemMapFields(shard.map.local, put);
    writeFileAtomically(file, out);
}

PemSampleShard readPemSampleShard(const std::string& file, int sample,
                                  const std::shared_ptr<const PemDistanceGeometry>& distance) {
    const std::string bytes = binary::readAll(file);
    binary::Reader in(file, bytes);
    checkHeader(in, file, kMapMagic, "PEM sample map");
    PemSampleShard shard;
    const Get get{in, file, "", distance};
    get("sample", shard.sample);
    if (shard.sample != sample)
        throw Error(file, "sample",
                    "expected sample " + std::to_string(sample) + ", got " +
                        std::to_string(shard.sample) + " (a file of another shard list)");
    get("left_out", shard.leftOut);
    PemLocalDecision& d = shard.decision;
    get("local", d.local), get("local_face_res", d.faceRes);
    get("sphere", d.sphere.centre), get("sphere", d.sphere.radius);
    pemMapFields(shard.map.map, Get{in, file, "map.", distance});
    pemMapFields(shard.map.local, Get{in, file, "local.", nullptr});
    checkEnd(in, file);
    return shard;
}

} // namespace specula

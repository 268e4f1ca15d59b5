// A PEM bake as shards (shard_pem.h) on the bowl room (a concave bowl that sees itself, so
// "auto" adds the local layer): trace shards and sample shards baked in shuffled orders, and
// the sample shards left to the merge, give the folder DIR/pem/ byte for byte as the
// in-process bake (cookProbe), with the local layer auto, on and off, and with the reflectors
// moving (parameter "reflector"). A sample shard or a merge with a trace shard missing names
// it and writes nothing; a shard of a scene edited since the list was written is refused; the
// shard files round-trip every field bit for bit and name the file and field when truncated.
// Also prints the shards' overhead against the plain bake (not asserted).
#include "assetcooker/lib/flavours/pem/pem_shard_files.h"
#include "assetcooker/lib/flavours/pem/shard_pem.h"
#include "engine/core/error.h"
#include "support/scratch_dir_test.h"
#include "tools/level_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iterator>
#include <random>
#include <set>

#include <sys/stat.h>

namespace specula {
namespace {

namespace fs = std::filesystem;

const std::string kBowlRoom = SPECULA_SOURCE_DIR "/assets/bowl_room/bowl_room.gltf";

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

class PemShard : public test::ScratchDirTest {
protected:
    PemShard() : ScratchDirTest("specula-pem-shards") {}

    static PemCookSettings settings(const std::string& localLayer) {
        PemCookSettings s;
        s.samples = 3;
        s.faceRes = 12;
        s.imageWidth = 64, s.imageHeight = 48;
        s.localLayer = localLayer;
        return s;
    }

    CookOptions cookOptions(const PemCookSettings& s, const std::string& out,
                            const std::string& scene = kBowlRoom) const {
        CookOptions o;
        o.scene = scene;
        o.out = (root_ / out).string();
        o.flavour = s;
        o.progress = false;
        return o;
    }

    // The shard list of a PEM bake into root_/out; returns the folder.
    std::string writeList(const PemCookSettings& s, const std::string& out,
                          const std::string& scene = kBowlRoom) const {
        ProbeScene loaded(scene, "");
        LevelCookOptions o;
        o.cook = cookOptions(s, out, scene);
        writeShardList(loaded, o, nullptr);
        return o.cook.out;
    }
};

// Every file of `dir` by name, with its bytes (no subfolders: a PEM folder has none).
std::map<std::string, std::string> folderBytes(const fs::path& dir) {
    return test::treeBytes(dir);
}

class PemShardLayers : public PemShard, public ::testing::WithParamInterface<const char*> {};

TEST_P(PemShardLayers, MergedInAnyOrderTheFolderIsTheInProcessBakeByteForByte) {
    const PemCookSettings s = settings(GetParam());
    const auto plainStart = std::chrono::steady_clock::now();
    const CookResult plain = cookProbe(cookOptions(s, "plain"), nullptr);
    const double plainSeconds = secondsSince(plainStart);
    const auto plainFiles = folderBytes(root_ / "plain");
    ASSERT_FALSE(plainFiles.empty());
    // The bowl sees itself: "auto" adds the local layer, "off" never does.
    EXPECT_EQ(std::get<PemAsset>(plain.asset).localLayer, std::string(GetParam()) != "off");

    std::mt19937 random(7);
    for (const bool mergeComputes : {false, true}) {
        const std::string dir = writeList(s, mergeComputes ? "merge-computes" : "shuffled");
        const ShardList list = readShardList(dir);
        ASSERT_EQ(list.shards.size(), 6u) << describeShards(list);
        std::vector<int> traces = {0, 1, 2}, samples = {3, 4, 5};
        std::shuffle(traces.begin(), traces.end(), random);
        std::shuffle(samples.begin(), samples.end(), random);
        double shardSeconds = 0;
        for (const int i : traces)
            shardSeconds += bakeShard(dir, i, nullptr).seconds;
        if (!mergeComputes)
            for (const int i : samples)
                shardSeconds += bakeShard(dir, i, nullptr).seconds;
        const LevelCookResult merged = mergeShards(dir, nullptr);
        EXPECT_EQ(merged.index, (fs::path(dir) / "pem" / "manifest.json").string());
        const auto files = folderBytes(fs::path(dir) / "pem");
        ASSERT_EQ(files.size(), plainFiles.size());
        for (const auto& [name, bytes] : plainFiles) {
            ASSERT_TRUE(files.count(name)) << name << " missing from the merged folder";
            EXPECT_TRUE(files.at(name) == bytes) << name << " differs from the in-process bake";
        }
        if (!mergeComputes)
            std::printf("[pem shards] local layer %s: 6 shards %.3f s + merge %.3f s vs the "
                        "in-process bake %.3f s (which also measures its fits)\n",
                        GetParam(), shardSeconds, merged.seconds, plainSeconds);
        // A second bake-shard finds every shard in the store.
        for (int i = 0; i < 6; ++i)
            EXPECT_TRUE(bakeShard(dir, i, nullptr).skipped) << i;
    }
}

INSTANTIATE_TEST_SUITE_P(LocalLayer, PemShardLayers, ::testing::Values("auto", "on", "off"));

// The reflectors move along a walk path (each trace shard moves them to its own t alone):
// the traces, baked in reverse, and the samples the merge computes give the plain bytes.
TEST_F(PemShard, ReflectorParameterShardsMergeToTheInProcessBake) {
    PemCookSettings s = settings("auto");
    s.parameter = "reflector";
    s.path = "line";
    cookProbe(cookOptions(s, "plain"), nullptr);
    const std::string dir = writeList(s, "sharded");
    for (int i = 2; i >= 0; --i)
        bakeShard(dir, i, nullptr);
    mergeShards(dir, nullptr);
    const auto plain = folderBytes(root_ / "plain");
    const auto merged = folderBytes(fs::path(dir) / "pem");
    ASSERT_EQ(merged.size(), plain.size());
    for (const auto& [name, bytes] : plain)
        EXPECT_TRUE(merged.count(name) && merged.at(name) == bytes) << name << " differs";
}

TEST_F(PemShard, EveryShardHasItsOwnHashAndTheSettingsAreInIt) {
    const ShardList a = readShardList(writeList(settings("auto"), "a"));
    const ShardList b = readShardList(writeList(settings("off"), "b"));
    std::set<std::string> hashes;
    for (const ShardList* list : {&a, &b})
        for (const Shard& s : list->shards)
            hashes.insert(s.hash);
    EXPECT_EQ(hashes.size(), 12u);
    // The same inputs: the same hashes.
    EXPECT_EQ(readShardList(writeList(settings("auto"), "c")).shards[4].hash, a.shards[4].hash);
    EXPECT_EQ(shardLabel(a, 4), "PEM sample 1: maps");
    // Under "off" a sample reads its own trace only.
    EXPECT_EQ(shardDependencies(a, 4), (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(shardDependencies(b, 4), (std::vector<int>{1}));
    EXPECT_EQ(leafShardsToBake((root_ / "a").string(), a), (std::vector<int>{0, 1, 2}));
}

TEST_F(PemShard, AMissingTraceShardIsNamedAndNothingIsWritten) {
    const std::string dir = writeList(settings("auto"), "pem");
    bakeShard(dir, 0, nullptr);
    bakeShard(dir, 2, nullptr);
    const ShardList list = readShardList(dir);
    for (const bool merge : {false, true}) {
        try {
            if (merge)
                mergeShards(dir, nullptr);
            else
                bakeShard(dir, 3, nullptr);
            FAIL() << "computed without trace shard 1";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("1 (PEM sample 1: trace, " + list.shards[1].hash + ")"),
                      std::string::npos)
                << what;
        }
    }
    EXPECT_FALSE(shardPresent(dir, list.shards[3]));
    EXPECT_FALSE(fs::exists(fs::path(dir) / "pem"));
}

TEST_F(PemShard, AShardOfASceneEditedSinceTheListIsRefused) {
    const fs::path copy = root_ / "scene";
    fs::create_directories(copy);
    for (const auto& f : fs::directory_iterator(fs::path(kBowlRoom).parent_path()))
        fs::copy_file(f.path(), copy / f.path().filename());
    const std::string gltf = (copy / fs::path(kBowlRoom).filename()).string();
    const std::string dir = writeList(settings("auto"), "pem", gltf);
    std::ifstream in(gltf);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    // panel_grid moves 10 cm: the tracer sees the whole room.
    const std::string from = " 3.98,", to = " 3.88,";
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << "panel_grid's translation not found";
    text.replace(at, from.size(), to);
    std::ofstream(gltf) << text;
    try {
        bakeShard(dir, 0, nullptr);
        FAIL() << "traced a shard of an edited scene";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "scene");
        EXPECT_NE(std::string(e.what()).find("changed since the shard list was written"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(shardPresent(dir, readShardList(dir).shards[0]));
}

// Distinct bits in every field, so a field dropped or swapped shows.
PemSamples distinctSamples() {
    PemSamples out(3);
    float v = 0.1f;
    auto next = [&v] { return v += 0.37f; };
    for (PemSample& s : out) {
        for (glm::vec3* f :
             {&s.x, &s.l, &s.target, &s.distant, &s.dxdX, &s.dxdY, &s.dldX, &s.dldY}) {
            const float a = next(), b = -next(), c = next();
            *f = glm::vec3(a, b, c);
        }
        s.selfHit = v > 10.f;
        s.onHull = v < 20.f;
    }
    return out;
}

TEST_F(PemShard, ShardFilesRoundTripBitForBitAndATruncatedOneIsNamed) {
    const PemSamples samples = distinctSamples();
    const std::string trace = (root_ / "t.trace").string();
    writePemTrace(samples, trace);
    const PemSamples read = readPemTrace(trace);
    ASSERT_EQ(read.size(), samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) {
        const PemSample &a = read[i], &b = samples[i];
        EXPECT_TRUE(a.x == b.x && a.l == b.l && a.target == b.target && a.distant == b.distant &&
                    a.selfHit == b.selfHit && a.onHull == b.onHull && a.dxdX == b.dxdX &&
                    a.dxdY == b.dxdY && a.dldX == b.dldX && a.dldY == b.dldY)
            << i;
    }

    const PemDecisionInputs inputs = readPemTraceDecisionInputs(trace);
    EXPECT_EQ(inputs.selfHits, pemDecisionInputs(samples).selfHits);
    EXPECT_EQ(inputs.offHull, pemDecisionInputs(samples).offHull);
    EXPECT_FALSE(inputs.offHull.empty());

    PemSampleShard shard;
    shard.sample = 2;
    shard.decision = {true, 4, {glm::vec3(0.25f, -1.f, 3.f), 0.75f}};
    shard.map.map.faceRes = 1;
    shard.map.map.boxMin = glm::vec3(-2.f), shard.map.map.boxMax = glm::vec3(3.f);
    shard.map.map.texels = std::vector<glm::vec3>(6, glm::vec3(0.5f, 1.5f, 2.5f));
    shard.map.local.faceRes = 1;
    shard.map.local.local = PemLocalSphere{glm::vec3(1.f), 2.f};
    shard.map.local.texels = std::vector<glm::vec3>(6, glm::vec3(0.125f));
    shard.map.local.alpha = std::vector<float>(6, 0.25f);
    const std::string map = (root_ / "s.map").string();
    writePemSampleShard(shard, map);
    const PemSampleShard back = readPemSampleShard(map, 2, nullptr);
    EXPECT_EQ(back.decision, shard.decision);
    EXPECT_EQ(back.map.map.texels, shard.map.map.texels);
    EXPECT_EQ(back.map.map.boxMax, shard.map.map.boxMax);
    EXPECT_EQ(back.map.local.local, shard.map.local.local);
    EXPECT_EQ(back.map.local.alpha, shard.map.local.alpha);
    EXPECT_EQ(back.map.map.distance, nullptr);
    EXPECT_THROW(readPemSampleShard(map, 1, nullptr), Error); // another sample's file
    EXPECT_FALSE(back.leftOut);
    shard.leftOut = true; // the sample's view held no reflector pixel
    writePemSampleShard(shard, map);
    EXPECT_TRUE(readPemSampleShard(map, 2, nullptr).leftOut);

    // A FIFO planted in a store on a shared disk: refused, naming it, never waited on.
    const std::string fifo = (root_ / "planted.trace").string();
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const auto& read : std::vector<std::function<void()>>{
             [&] { readPemTrace(fifo); }, [&] { readPemTraceDecisionInputs(fifo); },
             [&] { readPemSampleShard(fifo, 2, nullptr); }}) {
        try {
            read();
            ADD_FAILURE() << "read a FIFO";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), fifo);
            EXPECT_NE(std::string(e.what()).find("cannot read file"), std::string::npos)
                << e.what();
        }
    }

    const std::string bytes = [&] {
        std::ifstream f(trace, std::ios::binary);
        return std::string(std::istreambuf_iterator<char>(f), {});
    }();
    std::ofstream(trace, std::ios::binary) << bytes.substr(0, bytes.size() - 5);
    try {
        readPemTrace(trace);
        FAIL() << "read a truncated trace";
    } catch (const Error& e) {
        EXPECT_EQ(e.file(), trace);
        EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    }
}

} // namespace
} // namespace specula

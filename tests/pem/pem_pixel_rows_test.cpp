// One rendering-matrix row per displayed pixel (issue 12, Hakura §4: the target is the
// antialiased image): the rows against the mean of the sub-rays' twin weights computed here
// with the pixels found by projecting each ray's point into the camera; the inference on a
// closed-form scene (a mirror sphere in the box room of pem_room.h, everything analytic)
// against the antialiased image worked out here; determinism, the trace file's pixel field,
// and supersample 1 where the two kinds of rows are the same rows.
#include "assetcooker/lib/flavours/pem/pem_samples.h"
#include "assetcooker/lib/flavours/pem/pem_shard_files.h"
#include "components/reflection_probe/pem/pem_map_levels.h"
#include "engine/core/error.h"
#include "pem_fixtures.h"
#include "pem_room.h"
#include "support/probe_room.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>

using namespace specula;
using namespace specula::test;

namespace {

// The pixel of `camera` whose area holds the probe-local point x (row-major from the top).
int pixelOf(const CameraView& camera, glm::vec3 centre, glm::vec3 x) {
    const glm::vec4 clip = camera.viewProj() * glm::vec4(x + centre, 1.f);
    const float px = (clip.x / clip.w + 1.f) * 0.5f * float(camera.width);
    const float py = (1.f - clip.y / clip.w) * 0.5f * float(camera.height);
    return int(std::floor(py)) * camera.width + int(std::floor(px));
}

// The closed-form scene: a pinhole at `eye` looking at a mirror sphere (centre 0, radius r)
// inside the box room; each pixel's ss x ss sub-rays at the sub-pixel centres, those that
// hit the sphere reflected about its normal, their radiance the wall where they leave the
// room. Every sample's pixel is set, and at an odd ss its middle sub-ray is the centre.
PemSamples sphereInTheRoom(int width, int height, int ss, float r) {
    const glm::vec3 eye(0.3f, 0.4f, 2.6f);
    const glm::vec3 forward = glm::normalize(-eye),
                    right = glm::normalize(glm::cross(forward, {0, 1, 0}));
    const glm::vec3 up = glm::cross(right, forward);
    const float half = 0.42f; // tan of half the vertical field of view
    PemSamples out;
    for (int py = 0; py < height; ++py)
        for (int px = 0; px < width; ++px)
            for (int j = 0; j < ss; ++j)
                for (int i = 0; i < ss; ++i) {
                    const float u = (float(px) + (float(i) + 0.5f) / float(ss)) / float(width);
                    const float v = (float(py) + (float(j) + 0.5f) / float(ss)) / float(height);
                    const glm::vec3 d = glm::normalize(
                        forward + (2.f * u - 1.f) * half * float(width) / float(height) * right +
                        (1.f - 2.f * v) * half * up);
                    // |eye + t d|^2 = r^2, the nearer root.
                    const float b = glm::dot(eye, d), c = glm::dot(eye, eye) - r * r;
                    const float disc = b * b - c;
                    if (disc <= 0.f) continue;
                    PemSample s;
                    s.x = eye + (-b - std::sqrt(disc)) * d;
                    const glm::vec3 n = glm::normalize(s.x);
                    s.l = glm::normalize(glm::reflect(d, n));
                    s.target = wallRadiance(exitPoint(s.x, s.l, kRoomMin, kRoomMax));
                    s.pixel = py * width + px;
                    s.centre = ss % 2 == 1 && i == ss / 2 && j == ss / 2;
                    out.push_back(s);
                }
    return out;
}

PemInferOptions roomBox(int n, PemRows rows) {
    PemInferOptions o;
    o.faceRes = n;
    o.boxMin = kRoomMin;
    o.boxMax = kRoomMax;
    o.rows = rows;
    return o;
}

// Each pixel's sub-rays, grouped here (not by pemDataRows), with its antialiased radiance.
struct Pixel {
    std::vector<int> members;
    glm::dvec3 truth{0.0};
};
std::map<int, Pixel> pixelsOf(const PemSamples& samples) {
    std::map<int, Pixel> pixels;
    for (std::size_t s = 0; s < samples.size(); ++s) {
        Pixel& p = pixels[samples[s].pixel];
        p.members.push_back(int(s));
        p.truth += glm::dvec3(samples[s].target);
    }
    for (auto& [index, p] : pixels)
        p.truth /= double(p.members.size());
    return pixels;
}

// RMS over RGB of what each pixel shows against its antialiased radiance: its sub-rays' mean
// lookup, or (centre) its centre ray's lookup, over the pixels that have one.
double pixelRms(const PemMap& map, const PemSamples& samples, const std::map<int, Pixel>& pixels,
                bool centre = false) {
    const PemLookupCpu lookup(map);
    double sum = 0;
    int count = 0;
    for (const auto& [index, p] : pixels) {
        glm::dvec3 shown(0.0);
        int used = 0;
        for (const int s : p.members) {
            const PemSample& q = samples[std::size_t(s)];
            if (centre && !q.centre) continue;
            shown += glm::dvec3(lookup.radiance(q.x, q.l, q.footprint()));
            ++used;
        }
        if (used == 0) continue;
        const glm::dvec3 d = shown / double(used) - p.truth;
        sum += glm::dot(d, d);
        ++count;
    }
    return std::sqrt(sum / (3.0 * double(count)));
}

} // namespace

TEST(PemPixelRows, RowIsTheMeanOfItsSubRaysTwinRows) {
    // The room's reflectors as Embree traces them, 3 x 3 sub-rays a pixel with footprints,
    // against a map of MIP levels: each row's weights spread over two levels.
    ProbeRoom room;
    const int width = 48, height = 36, ss = 3;
    const glm::vec3 centre = room.probeCentre();
    const CameraView camera = room.camera(width, height);
    PemSampleOptions so;
    so.supersample = ss;
    const PemSamples samples = tracePemSamples(room.probeScene(), camera, centre, so);
    PemAsset header;
    header.faceRes = 32;
    header.mipLevels = 4;
    const Aabb box = pemMapBox(room.probeScene(), centre);
    header.boxMin = box.min;
    header.boxMax = box.max;
    const PemMap map = randomPemAsset(header, 1, 3u).samples.front().map;
    const PemLookupCpu lookup(map);

    // The tracer's pixel is the one the ray's reflector point projects into; its centre ray
    // projects onto the pixel's centre.
    std::map<int, std::vector<int>> byPixel;
    int centres = 0;
    for (std::size_t s = 0; s < samples.size(); ++s) {
        ASSERT_EQ(samples[s].pixel, pixelOf(camera, centre, samples[s].x)) << s;
        byPixel[samples[s].pixel].push_back(int(s));
        if (!samples[s].centre) continue;
        ++centres;
        const glm::vec4 clip = camera.viewProj() * glm::vec4(samples[s].x + centre, 1.f);
        const float px = (clip.x / clip.w + 1.f) * 0.5f * float(width);
        const float py = (1.f - clip.y / clip.w) * 0.5f * float(height);
        EXPECT_NEAR(px, float(samples[s].pixel % width) + 0.5f, 1e-3f) << s;
        EXPECT_NEAR(py, float(samples[s].pixel / width) + 0.5f, 1e-3f) << s;
    }
    const std::vector<std::vector<int>> rows = pemDataRows(samples, PemRows::Pixel);
    ASSERT_EQ(rows.size(), byPixel.size());
    EXPECT_LT(rows.size(), samples.size() / 4) << "most pixels need several sub-rays";
    EXPECT_EQ(pemDataRows(samples, PemRows::SubRay).size(), samples.size());

    const std::vector<std::vector<int>> centreRows = pemDataRows(samples, PemRows::Centre);
    EXPECT_EQ(int(centreRows.size()), centres);
    EXPECT_LT(centreRows.size(), rows.size()) << "edge pixels whose centre misses";
    std::vector<std::pair<int, double>> got;
    PemWeights w;
    for (const std::vector<int>& row : centreRows) {
        // The pixel's rays, its centre first; the weights its centre ray's alone.
        const int c = row.front();
        ASSERT_TRUE(samples[std::size_t(c)].centre);
        std::vector<int> sorted = row;
        std::sort(sorted.begin(), sorted.end());
        ASSERT_EQ(sorted, byPixel.at(samples[std::size_t(c)].pixel));
        pemRowWeights(lookup, samples, row, PemRows::Centre, got);
        const PemSample& p = samples[std::size_t(c)];
        lookup.weights(p.x, p.l, w, p.footprint());
        std::map<int, double> want;
        for (const auto& [t, weight] : w)
            want[t] += double(weight);
        ASSERT_EQ(got.size(), want.size());
        std::size_t i = 0;
        for (const auto& [t, weight] : want) {
            ASSERT_EQ(got[i].first, t);
            ASSERT_EQ(got[i].second, weight);
            ++i;
        }
    }
    int twoLevels = 0;
    for (const std::vector<int>& row : rows) {
        const std::vector<int>& want = byPixel.at(samples[std::size_t(row.front())].pixel);
        ASSERT_EQ(row, want);
        std::map<int, double> mean;
        for (const int s : row) {
            const PemSample& p = samples[std::size_t(s)];
            lookup.weights(p.x, p.l, w, p.footprint());
            for (const auto& [t, weight] : w)
                mean[t] += double(weight) / double(row.size());
        }
        pemRowWeights(lookup, samples, row, PemRows::Pixel, got);
        ASSERT_EQ(got.size(), mean.size());
        double total = 0;
        std::size_t i = 0;
        for (const auto& [t, weight] : mean) {
            ASSERT_EQ(got[i].first, t);
            ASSERT_NEAR(got[i].second, weight, 1e-12);
            total += got[i].second;
            ++i;
        }
        EXPECT_NEAR(total, 1.0, 1e-6);
        twoLevels += got.back().first >= PemMap::texelCount(map.faceRes);
    }
    std::printf("[ figures  ] room %dx%d x %d^2: %zu sub-rays in %zu pixel rows, %d of them "
                "reading level 1; %zu centre rows\n",
                width, height, ss, samples.size(), rows.size(), twoLevels, centreRows.size());
    EXPECT_GT(twoLevels, 0) << "the footprints must reach level 1";
}

TEST(PemPixelRows, InferredMapReproducesTheAntialiasedImageOfAClosedFormScene) {
    // More sub-rays than texels (the sub-ray rows cannot all be met) and fewer pixels than
    // the texels they see: pixel and centre rows are met to solver precision, so the map
    // drawn at those pixels (the sub-rays' mean lookup; the centre ray's lookup) is the
    // antialiased image. The sub-ray rows' map is printed beside them.
    const int width = 32, height = 24, ss = 3, n = 12;
    const PemSamples samples = sphereInTheRoom(width, height, ss, 0.6f);
    const std::map<int, Pixel> pixels = pixelsOf(samples);
    PemInferOptions o = roomBox(n, PemRows::Pixel);
    o.regularisation = 1e-4f;
    o.tolerance = 1e-12;
    o.maxIterations = 20000;
    const PemInference pixel = inferPemMap(samples, o);
    o.rows = PemRows::Centre;
    const PemInference centre = inferPemMap(samples, o);
    o.rows = PemRows::SubRay;
    const PemInference subRay = inferPemMap(samples, o);
    const int texels = PemMap::texelCount(n);
    const double rmsPixel = pixelRms(pixel.map, samples, pixels);
    const double rmsCentre = pixelRms(centre.map, samples, pixels, true);
    std::printf(
        "[ figures  ] sphere in the box room, %dx%d px x %d^2: %zu pixels (%d centre rows), "
        "%zu sub-rays, %d texels (%d seen): antialiased image RMS %.3g with pixel rows "
        "(%.3f s), %.3g with centre rows (%.3f s); sub-ray rows %.3g / %.3g (%.3f s)\n",
        width, height, ss, pixels.size(), centre.dataRows, samples.size(), texels,
        texels - pixel.unseenTexels, rmsPixel, pixel.seconds, rmsCentre, centre.seconds,
        pixelRms(subRay.map, samples, pixels), pixelRms(subRay.map, samples, pixels, true),
        subRay.seconds);
    ASSERT_GT(samples.size(), std::size_t(texels));
    ASSERT_LT(pixels.size(), std::size_t(texels - pixel.unseenTexels));
    EXPECT_EQ(pixel.dataRows, int(pixels.size()));
    EXPECT_EQ(subRay.dataRows, int(samples.size()));
    EXPECT_GT(centre.dataRows, int(pixels.size()) * 3 / 4);
    EXPECT_NEAR(pixel.residualRms, rmsPixel, 1e-9);
    EXPECT_NEAR(centre.residualRms, rmsCentre, 1e-9);
    EXPECT_LT(rmsPixel, 1e-4);
    EXPECT_LT(rmsCentre, 1e-4);
    EXPECT_LT(rmsPixel, 0.1 * pixelRms(subRay.map, samples, pixels));
    EXPECT_LT(rmsCentre, 0.1 * pixelRms(subRay.map, samples, pixels, true));
}

TEST(PemPixelRows, CentreRowsInferMipsBetterThanFilteredOnTheAntialiasedRoom) {
    // The cooker's path (tracePemSamples at 3 x 3 sub-rays a pixel, inferPemMap) on the
    // room's reflectors drawn small, as the display draws them: one lookup per pixel at its
    // centre with its footprint (the ray the rasteriser shades, traced here at supersample
    // 1), against the antialiased image (the mean of the pixel's traced sub-rays), on pixels
    // whose sub-rays all meet a reflector. Each kind of row infers every level together and
    // level 0 alone, whose box-filtered chain is the reference (Hakura §4). The centre rows
    // are the display's own rendering matrix: level 0 alone (more texels than pixels) then
    // shows the antialiased image to solver precision, and the inferred levels beat the
    // filtered ones by the 1 dB. The pixel rows model a supersampling display and the
    // sub-ray rows an aliased target: their figures are printed, not compared.
    ProbeRoom room;
    const int width = 160, height = 120, n = 64, levels = 6, ss = 3;
    const glm::vec3 centre = room.probeCentre();
    const CameraView camera = room.camera(width, height);
    PemSampleOptions so;
    so.supersample = 1;
    const PemSamples centres = tracePemSamples(room.probeScene(), camera, centre, so);
    so.supersample = ss;
    const PemSamples subRays = tracePemSamples(room.probeScene(), camera, centre, so);
    const std::map<int, Pixel> pixels = pixelsOf(subRays);
    PemSamples display; // centre rays, target the antialiased image
    for (PemSample p : centres) {
        const auto it = pixels.find(p.pixel);
        if (it == pixels.end() || int(it->second.members.size()) != ss * ss) continue;
        p.target = glm::vec3(it->second.truth);
        display.push_back(p);
    }
    ASSERT_GT(display.size(), 400u);
    const Aabb box = pemMapBox(room.probeScene(), centre);
    const auto psnrOf = [&](const PemMap& map) {
        const PemLookupCpu lookup(map);
        return pemSamplesPsnr(
            display, [&](const PemSample& p) { return lookup.radiance(p.x, p.l, p.footprint()); });
    };
    double level0Db[3] = {}, gain[3] = {};
    const PemRows kinds[3] = {PemRows::Centre, PemRows::Pixel, PemRows::SubRay};
    const char* names[3] = {"centre", "pixel", "sub-ray"};
    for (int k = 0; k < 3; ++k) {
        PemInferOptions o;
        o.faceRes = n;
        o.boxMin = box.min;
        o.boxMax = box.max;
        o.rows = kinds[k];
        const PemInference level0 = inferPemMap(subRays, o);
        o.mipLevels = levels;
        const PemInference mips = inferPemMap(subRays, o);
        const double inferred = psnrOf(mips.map);
        const double filtered = psnrOf(pemFilteredMips(level0.map, levels));
        gain[k] = inferred - filtered;
        level0Db[k] = psnrOf(level0.map);
        std::printf("[ figures  ] room %dx%d x %d^2, %zu display px, %s rows (%d): inferred MIPs "
                    "%.2f dB (%.2f s, %d iterations), filtered MIPs %.2f dB (%+.2f), level 0 "
                    "alone %.2f dB (%.2f s, %d iterations)\n",
                    width, height, ss, display.size(), names[k], mips.dataRows, inferred,
                    mips.seconds, mips.iterations[0], filtered, gain[k], level0Db[k],
                    level0.seconds, level0.iterations[0]);
    }
    EXPECT_GT(level0Db[0], 45.0); // RMS under 0.006 on every pixel row
    EXPECT_GT(level0Db[0], level0Db[1] + 10.0);
    EXPECT_GT(level0Db[0], level0Db[2] + 10.0);
    EXPECT_GT(gain[0], 1.0); // issue 12: MIP inference >= 1 dB over filtered MIPs
}

TEST(PemPixelRows, InferenceIsDeterministicAndTheTraceFileKeepsThePixel) {
    // A sharded bake infers from the trace file: the pixels it reads back give the same map,
    // bit for bit, as the trace in memory; and two inferences of one trace agree bit for bit.
    ProbeRoom room;
    const glm::vec3 centre = room.probeCentre();
    PemSampleOptions so;
    so.supersample = 3;
    so.layers = true;
    const PemSamples samples = tracePemSamples(room.probeScene(), room.camera(40, 30), centre, so);
    const std::string file = testing::TempDir() + "specula_pem_pixel_rows.trace";
    writePemTrace(samples, file);
    const PemSamples read = readPemTrace(file);
    std::filesystem::remove(file);
    ASSERT_EQ(read.size(), samples.size());
    for (std::size_t s = 0; s < samples.size(); ++s) {
        ASSERT_EQ(read[s].pixel, samples[s].pixel) << s;
        ASSERT_EQ(read[s].centre, samples[s].centre) << s;
    }

    const Aabb box = pemMapBox(room.probeScene(), centre);
    PemInferOptions o;
    o.faceRes = 16;
    o.mipLevels = 3;
    o.boxMin = box.min;
    o.boxMax = box.max;
    for (const PemRows rows : {PemRows::Pixel, PemRows::Centre}) {
        o.rows = rows;
        const PemInference a = inferPemMap(samples, o), b = inferPemMap(samples, o),
                           c = inferPemMap(read, o);
        EXPECT_TRUE(a.map.texels == b.map.texels);
        EXPECT_TRUE(a.map.texels == c.map.texels);
        EXPECT_LT(a.dataRows, int(samples.size()));
    }
}

TEST(PemPixelRows, OneRayPerPixelGivesTheSubRayRowsBitForBit) {
    // With supersample 1 a pixel row is its one ray's row: the cooked assets agree exactly.
    ProbeRoom room;
    PemCookSettings s;
    s.samples = 2;
    s.faceRes = 8;
    s.mipLevels = 2;
    s.imageWidth = 32;
    s.imageHeight = 24;
    s.localLayer = "on";
    s.rows = "pixel";
    const PemAsset pixel = cookPemAsset(room.probeScene(), s, {});
    s.rows = "subray";
    const PemAsset subRay = cookPemAsset(room.probeScene(), s, {});
    s.rows = "centre";
    const PemAsset centre = cookPemAsset(room.probeScene(), s, {});
    ASSERT_TRUE(pixel.localLayer && subRay.localLayer && centre.localLayer);
    ASSERT_EQ(pixel.samples.size(), subRay.samples.size());
    ASSERT_EQ(centre.samples.size(), subRay.samples.size());
    for (std::size_t k = 0; k < pixel.samples.size(); ++k)
        for (const PemAsset* other : {&pixel, &centre}) {
            const PemSampleMap &a = other->samples[k], &b = subRay.samples[k];
            EXPECT_TRUE(a.map.texels == b.map.texels) << k;
            EXPECT_TRUE(a.local.texels == b.local.texels) << k;
            EXPECT_TRUE(a.local.alpha == b.local.alpha) << k;
        }
}

TEST(PemPixelRows, BadRowsNameTheField) {
    // An unknown kind, and centre rows at an even supersample (no sub-ray at the centre).
    for (const auto& [rows, supersample] :
         {std::pair<std::string, int>{"pixels", 1}, std::pair<std::string, int>{"centre", 2}}) {
        PemCookSettings s;
        s.rows = rows;
        s.supersample = supersample;
        try {
            validatePemCookSettings(s, "scene.gltf");
            ADD_FAILURE() << "rows " << rows << " at supersample " << supersample << " accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.file(), "scene.gltf");
            EXPECT_EQ(e.field(), "rows");
        }
    }
    // Samples none of which is a pixel's centre give no centre row.
    PemSamples samples = randomRays(8, 1u, glm::vec3(0.f), 0.5f);
    for (PemSample& p : samples)
        p.pixel = 3;
    try {
        inferPemMap(samples, roomBox(4, PemRows::Centre));
        ADD_FAILURE() << "centre rows without a centre ray accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.field(), "samples");
    }
}

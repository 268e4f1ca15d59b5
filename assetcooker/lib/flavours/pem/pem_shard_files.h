#pragma once
// The files of a sharded PEM bake (shard_pem.h), little-endian (binary_file.h), each written
// atomically (beside, then renamed) and read back bit for bit, so that the merged asset is
// the one-machine bake's byte for byte:
//
//   <hash>.trace   one sample's traced reflector rays: "SPPEMTRC", u32 version, the local
//                  decision's inputs (pemDecisionInputs: u8 self hits, u64 count, f32 xyz
//                  each), u64 count, then every PemSample's fields in pemSampleFields' order
//   <hash>.map     one sample's inferred maps: "SPPEMMAP", u32 version, i32 sample, the local
//                  decision (u8 local, i32 face res, f32 sphere centre xyz, radius), then the
//                  distant map and the local map, each in pemMapFields' order
//
// pemSampleFields / pemMapFields list a struct's members once for the writer and the reader
// by structured binding: a member added to PemSample or PemMap is a compile error there
// until it is listed.
#include "assetcooker/lib/flavours/pem/pem_bake.h"

#include <string>

namespace specula {

void writePemTrace(const PemSamples& samples, const std::string& file);
// Throws Error naming the file and the field on a wrong header, a truncated or overlong file,
// or a value that cannot be (a count past the file's size, a flag not 0 or 1).
// The trace's samples; its decision inputs must agree with them.
PemSamples readPemTrace(const std::string& file);
// The trace's decision inputs alone, reading only that first part of the file (what a sample
// shard needs of the other samples' traces). Errors as readPemTrace.
PemDecisionInputs readPemTraceDecisionInputs(const std::string& file);

struct PemSampleShard {
    int sample = 0;
    PemLocalDecision decision;
    PemSampleMap map; // parameter unset (the list's k / samples); distance: the asset's
    // The sample's view held no reflector pixel (an empty trace): no map, left out of the asset.
    bool leftOut = false;
};

void writePemSampleShard(const PemSampleShard& shard, const std::string& file);
// `distance`: the asset's distance cube, which a map of distance geometry points to (null
// for box geometry). Throws Error naming the file and field as readPemTrace does, and
// "sample" when the file is another sample's.
PemSampleShard readPemSampleShard(const std::string& file, int sample,
                                  const std::shared_ptr<const PemDistanceGeometry>& distance);

} // namespace specula

// The GPU side of a distance probe's data, shared by every shader that runs the lookup
// (the reflector pass and the numerics harness): the parameter block of
// distance_params.glsl.h, uploaded as one uniform buffer, and the fetches
// distance_lookup.glsl.h expects. The includer adds fetchSky().
#ifndef SPECULA_DISTANCE_PROBE_GPU_GLSL
#define SPECULA_DISTANCE_PROBE_GPU_GLSL

// LAYER_TILES = 1: uLayers holds the composite alone and the object layers (1..) are tiles
// (distance_layer_tiles.h): a table from each tile to its atlas slot, an atlas of the tiles
// with content plus the empty one, each with a one-texel gutter of its face neighbours, so a
// bilinear fetch or gather inside a tile reads the texels the full face would. 0: every layer
// is whole in uLayers (the numerics harness uploads them so).
#ifndef LAYER_TILES
#define LAYER_TILES 0
#endif

// COMPRESSED_COMPOSITE = 1 (a probe cooked with --compress bc6h): uLayers holds radiance
// alone, as BC6H blocks, and uLayerDistance (R16F or R32F) the distances of the same texels.
#ifndef COMPRESSED_COMPOSITE
#define COMPRESSED_COMPOSITE 0
#endif

// Faces of layer L are array layers 6L .. 6L+5; RGB radiance, A distance.
uniform sampler2DArray uLayers;
#if COMPRESSED_COMPOSITE
uniform sampler2DArray uLayerDistance;
#endif

// The distance stored at texel t (x, y, array layer) of uLayers, and the 2 x 2 a bilinear
// fetch at uvw weighs.
float layerDistanceTexel(ivec3 t) {
#if COMPRESSED_COMPOSITE
    return texelFetch(uLayerDistance, t, 0).r;
#else
    return texelFetch(uLayers, t, 0).a;
#endif
}

vec4 layerDistanceGather(vec3 uvw) {
#if COMPRESSED_COMPOSITE
    return textureGather(uLayerDistance, uvw, 0);
#else
    return textureGather(uLayers, uvw, 3);
#endif
}

layout(std140, binding = kDistanceParamsBinding) uniform DistanceParamsUniforms {
    DistanceParamsBlock uDistance;
};

#if LAYER_TILES
uniform sampler2DArray uTileAtlas;
uniform isampler2DArray uTileTable;
uniform ivec2 uTileGrid;  // tile side in texels, tiles along a face side

// The texel origin (gutter included) and the atlas page of tile `tile` of object layer
// `layer`, as the table holds them (LayerTiles::slotOrigin).
ivec3 tileSlot(int layer, int face, ivec2 tile) {
    return texelFetch(uTileTable, ivec3(tile, (layer - 1) * 6 + face), 0).xyz;
}

// The atlas coordinate of face point f (cubeFaceUv) of object layer `layer`.
vec3 tileAtlasUv(int layer, vec3 f) {
    vec2 p = f.xy * float(uDistance.params.faceRes);
    ivec2 tile = min(ivec2(p) / uTileGrid.x, ivec2(uTileGrid.y - 1));
    ivec3 o = tileSlot(layer, int(f.z), tile);
    vec2 local = p - vec2(tile * uTileGrid.x) + vec2(o.xy) + 1.0;
    return vec3(local / vec2(textureSize(uTileAtlas, 0).xy), float(o.z));
}
#endif

float fetchDistance(int layer, vec3 dir) {
    int faceRes = uDistance.params.faceRes;
    vec3 f = cubeFaceUv(dir);
    ivec2 texel = min(ivec2(f.xy * float(faceRes)), ivec2(faceRes - 1));
#if LAYER_TILES
    if (layer > 0) {
        ivec2 tile = texel / uTileGrid.x;
        ivec3 o = tileSlot(layer, int(f.z), tile);
        return texelFetch(uTileAtlas, ivec3(o.xy + texel - tile * uTileGrid.x + 1, o.z), 0).a;
    }
#endif
    return layerDistanceTexel(ivec3(texel, layer * 6 + int(f.z)));
}

// The 2 x 2 stored distances a bilinear fetch at dir weighs (distance_seen.glsl.h).
vec4 fetchDistanceGather(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
#if LAYER_TILES
    if (layer > 0) return textureGather(uTileAtlas, tileAtlasUv(layer, f), 3);
#endif
    return layerDistanceGather(vec3(f.xy, float(layer * 6) + f.z));
}

vec3 fetchRadiance(int layer, vec3 dir) {
    vec3 f = cubeFaceUv(dir);
#if LAYER_TILES
    if (layer > 0) return textureLod(uTileAtlas, tileAtlasUv(layer, f), 0.0).rgb;
#endif
    return textureLod(uLayers, vec3(f.xy, float(layer * 6) + f.z), 0.0).rgb;
}

int layerMethod(int layer) { return uDistance.layers[layer].method; }
float layerAvgDistance(int layer) { return uDistance.layers[layer].avgDistance; }
vec3 layerBoxMin(int layer) { return uDistance.layers[layer].boxMin; }
vec3 layerBoxMax(int layer) { return uDistance.layers[layer].boxMax; }
float layerReach(int layer) { return uDistance.layers[layer].reach; }

DistanceParams lookupParams() { return uDistance.params; }

vec3 probeCentre() { return uDistance.params.centre; }

#endif

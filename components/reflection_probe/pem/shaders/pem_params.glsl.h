// Shared by GLSL and C++ (see engine/core/glsl_host.h): the parameter block of a PEM probe's
// reflector pass, laid out std140 so the C++ struct is uploaded as is (pem_store.cpp) and
// read by the CPU twin (pem_probe_cpu.h) too. A parameter edit rewrites this block only.
//
// std140 by hand: each vec3 shares its 16-byte slot with the 4-byte scalar after it, the
// struct is a multiple of 16 bytes, padding is named, no bool.
#ifndef SPECULA_PEM_PARAMS_GLSL_H
#define SPECULA_PEM_PARAMS_GLSL_H

// The uniform-buffer binding point, apart from the other flavours' (distance 0, test 3).
SHARED_CONST int kPemParamsBinding = 4;
// The storage-buffer binding of the drawn reflector's hull flags (pem_hull.h).
SHARED_CONST int kPemHullBinding = 5;

struct PemParams {
    vec3 boxMin; // probe-local map box (every sample's)
    int faceRes; // texels along a face edge
    vec3 boxMax;
    float wb;    // weight of sample b; sample a gets 1 - wb (pem_blend.h)
    vec3 centre; // world position of the maps' origin: reflector points are made local
    int layerA;  // first array layer of sample a (6 a: faces +X -X +Y -Y +Z -Z follow)
    int layerB;  // first array layer of sample b
    // Distance geometry (GEOMETRY_DISTANCE shaders; zero for box maps): the distance cube's
    // face resolution and the secant search's parameters (PemDistanceGeometry).
    int distanceFaceRes;
    float dInf;
    float range;
    float tolerance;
    int maxSteps;
    // The local layer (HAS_LOCAL_LAYER shaders; zero without one): its cube's face
    // resolution and sphere (PemLocalSphere, probe-local).
    int localFaceRes;
    int mapLevels; // MIP levels of every sample's distant map (PEM_MIP shaders read them)
    vec3 localCentre;
    float localRadius;
};

#ifdef __cplusplus
static_assert(offsetof(PemParams, faceRes) == 12 && offsetof(PemParams, boxMax) == 16);
static_assert(offsetof(PemParams, wb) == 28 && offsetof(PemParams, centre) == 32);
static_assert(offsetof(PemParams, layerA) == 44 && offsetof(PemParams, layerB) == 48);
static_assert(offsetof(PemParams, distanceFaceRes) == 52 && offsetof(PemParams, dInf) == 56);
static_assert(offsetof(PemParams, range) == 60 && offsetof(PemParams, tolerance) == 64);
static_assert(offsetof(PemParams, maxSteps) == 68 && offsetof(PemParams, localFaceRes) == 72);
static_assert(offsetof(PemParams, mapLevels) == 76);
static_assert(offsetof(PemParams, localCentre) == 80 && offsetof(PemParams, localRadius) == 92);
static_assert(sizeof(PemParams) == 96);
#endif

#endif

/* Embree's own BVH built at RTC_BUILD_QUALITY_MEDIUM (embreex's default, what
 * benches/peers/bvh_embree.py measures) and at RTC_BUILD_QUALITY_HIGH (what Mitsuba 3 asks
 * for: src/render/scene_embree.inl, `rtcSetSceneBuildQuality(s.accel, RTC_BUILD_QUALITY_HIGH)`;
 * on triangle meshes it adds spatial splits), traced with the same rays on one thread. It
 * answers one question: how much of Mitsuba's speed on mesh scenes comes from spatial splits.
 *
 *   benches/peers/embree_quality.sh [--pathtrace BIN] [--mesh bunny|sphere|soup|grid] ...
 *
 * builds this file against the libembree4 of .venv-embree (benches/peers/bvh_embree_setup.sh)
 * and runs it on an export of `pathtrace bench bvh --export` (or on the suite's mesh-1m grid).
 * The few declarations below are Embree 4's public API (include/embree4/rtcore*.h): the wheel
 * ships the library without its headers.
 *
 * Input (the export format of crates/pathtrace-cli/src/bvh_export.rs): "PTBVHEX1", u64
 * triangles, u64 rays, f32 corners (9 per triangle), f32 rays (origin, direction), f32 our
 * distances. Output: one JSON line per quality with build seconds and M rays/s.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct RTCDeviceTy *RTCDevice;
typedef struct RTCSceneTy *RTCScene;
typedef struct RTCGeometryTy *RTCGeometry;

enum { RTC_BUILD_QUALITY_MEDIUM = 1, RTC_BUILD_QUALITY_HIGH = 2 };
enum { RTC_GEOMETRY_TYPE_TRIANGLE = 0 };
enum { RTC_BUFFER_TYPE_INDEX = 0, RTC_BUFFER_TYPE_VERTEX = 1 };
enum { RTC_FORMAT_UINT3 = 0x5003, RTC_FORMAT_FLOAT3 = 0x9003 };

/* RTCRay (48 bytes) then RTCHit; padded well past the hit's end so either instance-level
 * layout of Embree 4.x fits. */
struct RayHit {
    float org_x, org_y, org_z, tnear;
    float dir_x, dir_y, dir_z, time;
    float tfar;
    uint32_t mask, id, flags;
    float ng_x, ng_y, ng_z, u, v;
    uint32_t prim_id, geom_id, inst_id[4];
    uint32_t pad[8];
} __attribute__((aligned(16)));

RTCDevice rtcNewDevice(const char *config);
RTCScene rtcNewScene(RTCDevice device);
void rtcSetSceneBuildQuality(RTCScene scene, int quality);
RTCGeometry rtcNewGeometry(RTCDevice device, int type);
void *rtcSetNewGeometryBuffer(RTCGeometry g, int type, unsigned slot, int format, size_t stride, size_t count);
void rtcCommitGeometry(RTCGeometry g);
unsigned rtcAttachGeometry(RTCScene scene, RTCGeometry g);
void rtcReleaseGeometry(RTCGeometry g);
void rtcCommitScene(RTCScene scene);
void rtcReleaseScene(RTCScene scene);
void rtcIntersect1(RTCScene scene, struct RayHit *rayhit, void *args);

static double thread_seconds(void) {
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

static double wall_seconds(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: %s EXPORT RUNS\n", argv[0]);
        return 2;
    }
    FILE *f = fopen(argv[1], "rb");
    if (!f) {
        perror(argv[1]);
        return 1;
    }
    char magic[8];
    uint64_t tris, rays;
    if (fread(magic, 1, 8, f) != 8 || memcmp(magic, "PTBVHEX1", 8) != 0 || fread(&tris, 8, 1, f) != 1 ||
        fread(&rays, 8, 1, f) != 1) {
        fprintf(stderr, "%s: not a pathtrace BVH export\n", argv[1]);
        return 1;
    }
    float *corners = malloc(tris * 9 * sizeof(float));
    float *ray = malloc(rays * 6 * sizeof(float));
    if (!corners || !ray || fread(corners, sizeof(float), tris * 9, f) != tris * 9 ||
        fread(ray, sizeof(float), rays * 6, f) != rays * 6) {
        fprintf(stderr, "%s: truncated\n", argv[1]);
        return 1;
    }
    fclose(f);
    int runs = atoi(argv[2]);
    if (runs < 1) {
        fprintf(stderr, "%s: RUNS must be a positive integer, got '%s'\n", argv[0], argv[2]);
        return 2;
    }
    RTCDevice device = rtcNewDevice("threads=1");
    const int qualities[2] = {RTC_BUILD_QUALITY_MEDIUM, RTC_BUILD_QUALITY_HIGH};
    const char *names[2] = {"medium", "high"};
    for (int run = 0; run < runs; ++run) {
        for (int k = 0; k < 2; ++k) {
            int q = (run % 2) ? 1 - k : k; /* alternate which quality goes first */
            RTCScene scene = rtcNewScene(device);
            rtcSetSceneBuildQuality(scene, qualities[q]);
            RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
            float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, tris * 3);
            uint32_t *idx = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, tris);
            memcpy(v, corners, tris * 9 * sizeof(float));
            for (uint64_t i = 0; i < tris * 3; ++i) idx[i] = (uint32_t)i;
            rtcCommitGeometry(g);
            rtcAttachGeometry(scene, g);
            rtcReleaseGeometry(g);
            double b0 = wall_seconds();
            rtcCommitScene(scene);
            double build = wall_seconds() - b0;
            uint64_t hits = 0;
            double sum_t = 0.0;
            double t0 = thread_seconds();
            for (uint64_t r = 0; r < rays; ++r) {
                struct RayHit rh;
                memset(&rh, 0, sizeof rh);
                const float *o = ray + r * 6;
                rh.org_x = o[0], rh.org_y = o[1], rh.org_z = o[2], rh.tnear = 0.0f;
                rh.dir_x = o[3], rh.dir_y = o[4], rh.dir_z = o[5];
                rh.tfar = 1e30f, rh.mask = 0xffffffffu;
                rh.geom_id = rh.inst_id[0] = 0xffffffffu;
                rtcIntersect1(scene, &rh, NULL);
                if (rh.geom_id != 0xffffffffu) {
                    hits++;
                    sum_t += rh.tfar;
                }
            }
            double trace = thread_seconds() - t0;
            printf("{\"run\": %d, \"quality\": \"%s\", \"triangles\": %llu, \"rays\": %llu, \"build_s\": %.4f, "
                   "\"mrays_per_s\": %.4f, \"hits\": %llu, \"sum_t\": %.6e}\n",
                   run, names[q], (unsigned long long)tris, (unsigned long long)rays, build, rays / trace / 1e6,
                   (unsigned long long)hits, sum_t);
            fflush(stdout);
            rtcReleaseScene(scene);
        }
    }
    return 0;
}

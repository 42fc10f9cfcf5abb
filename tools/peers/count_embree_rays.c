/* LD_PRELOAD shim for tools/peers/compare_povray.py: counts the rays a program traces through
 * Embree 3's single-ray API (rtcIntersect1, rtcOccluded1; all that Embree's `pathtracer`
 * sample calls) and its ray streams (rtcIntersect1M, rtcOccluded1M: M rays each; Glint traces
 * camera rays as streams), and prints the totals to stderr at exit. Build:
 *   cc -O2 -shared -fPIC -o count_embree_rays.so count_embree_rays.c -ldl
 * Per-thread counters in padded slots, so counting adds no shared-cache-line traffic. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

enum { kSlots = 256 };
struct Slot {
  uint64_t intersect, occluded;
  char pad[48];
};
static struct Slot slots[kSlots];
static atomic_int next_slot;
static __thread int my_slot = -1;

static struct Slot* slot(void) {
  if (my_slot < 0) my_slot = atomic_fetch_add(&next_slot, 1) % kSlots;
  return &slots[my_slot];
}

typedef void (*Fn)(void*, void*, void*);
static Fn real_intersect, real_occluded;

void rtcIntersect1(void* scene, void* context, void* rayhit) {
  if (!real_intersect) real_intersect = (Fn)dlsym(RTLD_NEXT, "rtcIntersect1");
  slot()->intersect++;
  real_intersect(scene, context, rayhit);
}

void rtcOccluded1(void* scene, void* context, void* ray) {
  if (!real_occluded) real_occluded = (Fn)dlsym(RTLD_NEXT, "rtcOccluded1");
  slot()->occluded++;
  real_occluded(scene, context, ray);
}

typedef void (*StreamFn)(void*, void*, void*, unsigned, size_t);
static StreamFn real_intersect_m, real_occluded_m;

void rtcIntersect1M(void* scene, void* context, void* rayhits, unsigned m, size_t stride) {
  if (!real_intersect_m) real_intersect_m = (StreamFn)dlsym(RTLD_NEXT, "rtcIntersect1M");
  slot()->intersect += m;
  real_intersect_m(scene, context, rayhits, m, stride);
}

void rtcOccluded1M(void* scene, void* context, void* rays, unsigned m, size_t stride) {
  if (!real_occluded_m) real_occluded_m = (StreamFn)dlsym(RTLD_NEXT, "rtcOccluded1M");
  slot()->occluded += m;
  real_occluded_m(scene, context, rays, m, stride);
}

/* The totals count stream rays with single ones (the names say "1": rays, not calls). */
__attribute__((destructor)) static void report(void) {
  uint64_t a = 0, b = 0;
  for (int i = 0; i < kSlots; ++i) {
    a += slots[i].intersect;
    b += slots[i].occluded;
  }
  fprintf(stderr, "embree-rays intersect1 %llu occluded1 %llu\n", (unsigned long long)a,
          (unsigned long long)b);
}

// Volumes (shared/volume.h): the field (a grid's, or an unstructured mesh's: unstructured.glsl) and its
// transfer function at a point, and the two estimators that
// march a ray through a volume's macrocell grid by a 3D DDA: delta tracking (where the ray first collides,
// for free-flight sampling) and ratio tracking (its transmittance, for shadow rays). Both are unbiased for
// any majorant that bounds the extinction, which the macrocells do, and, in macrocells crossed cell by
// cell, the bounds of the interpolant along the ray in each cell. Every step of both counts against the
// invocation's step budget (lavapipe silently ends a loop after 65,535 iterations); a march that spends it
// stops where it is and is parked for a resume round (VolumeParking below), never given a wrong answer.
// Needs pt_common.glsl and rng.glsl.
#ifndef RIPPLE_VOLUME_GLSL
#define RIPPLE_VOLUME_GLSL

#include "features.glsl"
#include "shared/volume.h"
#include "unstructured.glsl"
#include "nanovdb.glsl"
#include "amr.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer VolumesRef { VolumeRecord volumes[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer VolumeDataRef { float values[]; };

// The most tracking steps one invocation may take: VOLUME_STEP_CHUNKS loops of VOLUME_STEP_CHUNK, nested
// because lavapipe ends any one loop after 65,535 iterations. The budget an invocation is given
// (VolumeParkingHeader.stepBudget) is at most this; the host checks it.
const uint VOLUME_STEP_CHUNK = 32768u;
const uint VOLUME_STEP_CHUNKS = 32u;

// Random numbers for the tracking loops: a stream keyed like random4 (rng.glsl), 4 numbers per hash.
struct VolumeRng {
    uvec4 key;
    uint counter;
    uint used;
    uvec4 bits;
};

// A resumed march draws from a stream of its own round (the exponential steps are memoryless, so fresh
// numbers from where it stopped leave the estimate unbiased); round 0 is the stream of a march never parked.
VolumeRng volumeRng(uint pixel, uint sampleIndex, uint bounce, uint group, uint seed, uint round) {
    return VolumeRng(uvec4(pixel, sampleIndex, (bounce << 4u) | group, seed ^ (round * 0x632BE5ABu)), 0u, 4u, uvec4(0u));
}

uint volumeRandomBits(inout VolumeRng r) {
    if (r.used == 4u) {
        r.bits = pcg4d(uvec4(r.key.xy, r.key.z | (r.counter << 16u), r.key.w));
        ++r.counter;
        r.used = 0u;
    }
    return r.bits[r.used++];
}

// Uniform in [0, 1) in steps of 2^-24 (so 1 - u is never 0).
float volumeRandom(inout VolumeRng r) {
    return float(volumeRandomBits(r) >> 8u) * (1.0 / 16777216.0);
}

// True with probability p, resolved to 2^-32 near 0: delta tracking accepts collisions with probability
// extinction / majorant, which in stiff media is far below the 2^-24 step of volumeRandom (whose
// P(u < p) = 2^-24 for any tiny p > 0 would turn a million null collisions into a few percent of false
// real ones).
bool volumeChance(inout VolumeRng r, float p) {
    uint bits = volumeRandomBits(r);
    if (p >= 1.0) return true;
    // u = bits / 2^32 in two parts, exact near 0 where it matters.
    float u = (float(bits >> 8u) + float(bits & 0xFFu) * (1.0 / 256.0)) * (1.0 / 16777216.0);
    return u < p;
}

float voxel(VolumeRecord v, VolumeDataRef data, uvec3 i) {
    return VolumeDataRef(v.voxels).values[(i.z * v.dimY + i.y) * v.dimX + i.x];
}

// The field at grid-space point g (voxel i at i), clamped to the grid.
float fieldValue(VolumeRecord v, VolumeDataRef data, vec3 g) {
    g = clamp(g, vec3(0.0), v.gridExtent.xyz);
    if (v.filterMode == VOLUME_FILTER_NEAREST) return voxel(v, data, uvec3(g + 0.5));
    uvec3 last = uvec3(v.dimX - 1u, v.dimY - 1u, v.dimZ - 1u);
    uvec3 i0 = min(uvec3(g), last);
    uvec3 i1 = min(i0 + 1u, last);
    vec3 w = g - vec3(i0);
    float c00 = mix(voxel(v, data, uvec3(i0.x, i0.y, i0.z)), voxel(v, data, uvec3(i1.x, i0.y, i0.z)), w.x);
    float c10 = mix(voxel(v, data, uvec3(i0.x, i1.y, i0.z)), voxel(v, data, uvec3(i1.x, i1.y, i0.z)), w.x);
    float c01 = mix(voxel(v, data, uvec3(i0.x, i0.y, i1.z)), voxel(v, data, uvec3(i1.x, i0.y, i1.z)), w.x);
    float c11 = mix(voxel(v, data, uvec3(i0.x, i1.y, i1.z)), voxel(v, data, uvec3(i1.x, i1.y, i1.z)), w.x);
    return mix(mix(c00, c10, w.y), mix(c01, c11, w.y), w.z);
}

// Where a field value falls in the transfer-function table, 0 .. tableSize - 1 (a NaN value at 0). Never
// decreasing in the value, so a range of values maps to a range of positions that holds each value's own.
float tablePosition(VolumeRecord v, float value) {
    float x = (value - v.valueRange.x) * v.valueRange.y;
    return (x >= 0.0 ? min(x, 1.0) : 0.0) * float(v.tableSize - 1u);
}

// (albedo rgb, extinction per world unit) of a field value, linearly interpolated in the table.
vec4 transferFunction(VolumeRecord v, VolumeDataRef data, float value) {
    float x = tablePosition(v, value);
    uint i0 = min(uint(x), v.tableSize - 2u);
    float w = x - float(i0);
    uint at = v.tableOffset + 4u * i0;
    vec4 a = vec4(data.values[at], data.values[at + 1u], data.values[at + 2u], data.values[at + 3u]);
    vec4 b = vec4(data.values[at + 4u], data.values[at + 5u], data.values[at + 6u], data.values[at + 7u]);
    return mix(a, b, w);
}

// (albedo rgb, extinction per world unit) at grid-space point g: the transfer function of the field there;
// none outside an unstructured mesh's cells or an AMR hierarchy's blocks.
// `mesh`: an unstructured mesh's header (read once per march).
vec4 mediumAt(VolumeRecord v, VolumeDataRef data, vec3 g, UnstructuredHeader mesh) {
    if (hasFeature(FEATURE_UNSTRUCTURED_VOLUMES) && v.kind == VOLUME_KIND_UNSTRUCTURED) {
        float value;
        return unstructuredValue(v.voxels, mesh, g, value) ? transferFunction(v, data, value) : vec4(0.0);
    }
    if (hasFeature(FEATURE_NANOVDB_VOLUMES) && v.kind == VOLUME_KIND_NANOVDB)
        return transferFunction(v, data, nanovdbValue(v.voxels, g, v.filterMode));
    if (hasFeature(FEATURE_AMR_VOLUMES) && v.kind == VOLUME_KIND_AMR) {
        float value;
        return amrValue(v.voxels, uvec3(v.macroX, v.macroY, v.macroZ), g, value) ? transferFunction(v, data, value) : vec4(0.0);
    }
    return transferFunction(v, data, fieldValue(v, data, g));
}

// The largest extinction the table gives over voxel values [lowest, highest], from the range-maximum table
// after it (core/scene/VolumeTable.cpp): the entries from below the range's first position to above its
// last (tablePosition, as transferFunction reads them), so at least the interpolated table's maximum
// there; raised by 1e-5 as the macrocell majorants are.
float extinctionMax(VolumeRecord v, VolumeDataRef data, float lowest, float highest) {
    float p0 = tablePosition(v, lowest), p1 = max(tablePosition(v, highest), p0);
    uint first = min(uint(p0), v.tableSize - 1u), last = min(uint(ceil(p1)), v.tableSize - 1u);
    uint level = findMSB(last - first + 1u);
    uint at = v.tableOffset + 4u * v.tableSize + level * v.tableSize;
    return max(data.values[at + first], data.values[at + last + 1u - (1u << level)]) * (1.0 + 1e-5);
}

// The trilinear interpolant inside one cell along a ray segment [entry, exit] is a cubic in s = 0..1 over
// the segment: its power coefficients (x + y s + z s^2 + w s^3), from its values at s = 0, 1/3, 2/3, 1.
vec4 cellCubic(VolumeRecord v, VolumeDataRef data, ivec3 cell, vec3 o, vec3 d, float entry, float exit) {
    uvec3 i0 = uvec3(cell), i1 = min(i0 + 1u, uvec3(v.dimX - 1u, v.dimY - 1u, v.dimZ - 1u));
    vec4 below = vec4(voxel(v, data, uvec3(i0.x, i0.y, i0.z)), voxel(v, data, uvec3(i1.x, i0.y, i0.z)),
                      voxel(v, data, uvec3(i0.x, i1.y, i0.z)), voxel(v, data, uvec3(i1.x, i1.y, i0.z)));
    vec4 above = vec4(voxel(v, data, uvec3(i0.x, i0.y, i1.z)), voxel(v, data, uvec3(i1.x, i0.y, i1.z)),
                      voxel(v, data, uvec3(i0.x, i1.y, i1.z)), voxel(v, data, uvec3(i1.x, i1.y, i1.z)));
    vec4 f;
    for (int j = 0; j < 4; ++j) {
        vec3 w = o + mix(entry, exit, float(j) / 3.0) * d - vec3(cell);
        vec4 z = mix(below, above, w.z);
        vec2 y = mix(z.xz, z.yw, w.x);
        f[j] = mix(y.x, y.y, w.y);
    }
    // Newton's forward differences on the nodes, expanded in powers of s.
    float d1 = f[1] - f[0], d2 = f[2] - 2.0 * f[1] + f[0], d3 = f[3] - 3.0 * f[2] + 3.0 * f[1] - f[0];
    return vec4(f[0], 3.0 * d1 - 1.5 * d2 + d3, 4.5 * (d2 - d3), 4.5 * d3);
}

float cubicAt(vec4 a, float s) {
    return a.x + s * (a.y + s * (a.z + s * a.w));
}

// The range of cubic a over s in [s0, s0 + h], bounded by its Bernstein coefficients there (their hull
// holds the curve). Not finite (voxel values near the float limit overflow the coefficients): every value.
vec2 cubicRange(vec4 a, float s0, float h) {
    float p0 = cubicAt(a, s0);
    float p1 = (a.y + s0 * (2.0 * a.z + 3.0 * a.w * s0)) * h;
    float p2 = (a.z + 3.0 * a.w * s0) * h * h;
    float p3 = a.w * h * h * h;
    vec4 b = vec4(p0, p0 + p1 / 3.0, p0 + (2.0 * p1 + p2) / 3.0, p0 + p1 + p2 + p3);
    if (any(isnan(b)) || any(isinf(b))) return vec2(-INFINITY, INFINITY);
    return vec2(min(min(b.x, b.y), min(b.z, b.w)), max(max(b.x, b.y), max(b.z, b.w)));
}

// Ratio tracking's transmittance below which Russian roulette decides whether the march goes on.
const float VOLUME_ROULETTE_BELOW = 0.1;

// Cell-by-cell tracking (volumes whose record has cellByCell). A macrocell whose majorant's optical depth
// over one cell crossing (on average along this ray) reaches VOLUME_REFINE_DEPTH is crossed cell by cell:
// in each cell the ray's interpolant is a cubic (cellCubic), and the majorant from t to the cell's exit is
// the largest extinction over the cubic's range there, bounded again after each null collision. Where a
// thin shell of the transfer function crosses a cell, the majorant is the shell's peak only up to where
// the ray passes it, and zero in cells the shell misses. Tentative collisions there read no voxels: the
// cubic gives the value. On lavapipe a cell crossing costs about what a null collision does, hence the
// depth of one.

const uint TRACK_DELTA = 0u;  // stop at the first real collision
const uint TRACK_RATIO = 1u;  // product of (1 - extinction / majorant) over tentative collisions

struct TrackResult {
    float t;             // delta: where the ray collided (tmax when it did not); ran out: where it stopped
    float transmittance; // delta: 0 at a collision, 1 without; ratio: the estimate (so far, when ran out)
    vec3 albedo;         // delta: the albedo at the collision
    bool ranOut;         // the step budget ended the march at t: resume it from there
    uint collisions;     // tentative collisions (delta: the real one, if any, and the null ones before it)
};

// Adds n to one of PathCounters' 64-bit sums (two words, low first): the carry goes to the high word.
#define countVolumeSteps(counters, field, n)                                        \
    {                                                                               \
        uint countedBefore = atomicAdd(counters.field[0], n);                       \
        if (countedBefore + (n) < countedBefore) atomicAdd(counters.field[1], 1u);  \
    }

// A 3D DDA over cells of `size` grid units (macrocells, or the field's cells at size 1), begun at t: the cell
// holding o + t d, clamped to [0, last], and per axis the t of its next face, stepped past faces at or
// behind t (a march resumed on a face, where it parked after crossing it, may round into the cell behind
// the face, and with every budget it would cross that face again).
void ddaBegin(vec3 o, vec3 d, vec3 inv, ivec3 stepDir, float t, float size, ivec3 last, out ivec3 cell, out vec3 next) {
    cell = clamp(ivec3(floor((o + t * d) / size)), ivec3(0), last);
    next = mix(vec3(INFINITY), (vec3(cell + max(stepDir, ivec3(0))) * size - o) * inv, notEqual(stepDir, ivec3(0)));
    vec3 delta = abs(size * inv);
    for (int k = 0; k < 3; ++k) {
        for (int behind = 0; behind < 2 && next[k] <= t; ++behind) {
            cell[k] += stepDir[k];
            next[k] += delta[k];
        }
    }
}

// The DDA into the next cell, across the nearest face (`delta`: t across one cell per axis).
void ddaStep(ivec3 stepDir, vec3 delta, inout ivec3 cell, inout vec3 next) {
    if (next.x <= next.y && next.x <= next.z) {
        cell.x += stepDir.x;
        next.x += delta.x;
    } else if (next.y <= next.z) {
        cell.y += stepDir.y;
        next.y += delta.y;
    } else {
        cell.z += stepDir.z;
        next.z += delta.z;
    }
}

// Marches world ray origin + t * direction, t in [tmin, tmax], through volume v, taking steps from
// `budget` (left as what remains). A step is a tentative collision, a macrocell entered, or in a macrocell
// crossed cell by cell, a cell entered or the rest of one crossed. `cellByCell` is a constant at each call
// (trackVolume below), so the march of a volume that has no such macrocell carries none of that code.
TrackResult trackVolumeMarch(VolumeRecord v, VolumeDataRef data, vec3 origin, vec3 direction, float tmin, float tmax,
                             uint mode, bool cellByCell, inout VolumeRng rng, inout uint budget) {
    TrackResult result = TrackResult(tmax, 1.0, vec3(0.0), false, 0u);
    mat3x4 toGrid = mat3x4(v.worldToGrid[0], v.worldToGrid[1], v.worldToGrid[2]);
    vec3 o = vec4(origin, 1.0) * toGrid;
    vec3 d = vec4(direction, 0.0) * toGrid;
    float speed = length(direction);  // world distance per unit of t
    // The ray's extent inside the grid box.
    vec3 inv = safeReciprocal(d);
    vec3 ta = (vec3(0.0) - o) * inv, tb = (v.gridExtent.xyz - o) * inv;
    float t0 = max(tmin, max(max(min(ta.x, tb.x), min(ta.y, tb.y)), min(ta.z, tb.z)));
    float t1 = min(tmax, min(min(max(ta.x, tb.x), max(ta.y, tb.y)), max(ta.z, tb.z)));
    if (!(t0 < t1) || !(speed > 0.0)) return result;

    // DDA over macrocells, starting in the one holding the entry point.
    ivec3 macroDims = ivec3(v.macroX, v.macroY, v.macroZ);
    ivec3 stepDir = ivec3(sign(d));
    ivec3 cell;
    vec3 tNext;
    ddaBegin(o, d, inv, stepDir, t0, float(VOLUME_MACROCELL), macroDims - 1, cell, tNext);
    vec3 tDelta = abs(float(VOLUME_MACROCELL) * inv);
    if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, macroDims))) return result;
    float t = t0;
    uint cellIndex = (uint(cell.z) * v.macroY + uint(cell.y)) * v.macroX + uint(cell.x);
    float majorant = data.values[v.majorantOffset + cellIndex] * speed;

    // Cell-by-cell state: whether this macrocell is crossed cell by cell, the cell the march is in (a
    // DDA over cells, begun where the macrocell is entered: voxelExit is -inf until then) and the cubic over
    // that cell's segment [voxelEntry, voxelExit].
    float cellCrossing = 1.0 / (abs(d.x) + abs(d.y) + abs(d.z));  // mean t across one cell
    bool refined = cellByCell && majorant * cellCrossing >= VOLUME_REFINE_DEPTH;
    ivec3 voxelCell = ivec3(0);
    vec3 voxelNext = vec3(0.0), voxelDelta = abs(inv);
    float voxelEntry = 0.0, voxelExit = -INFINITY;
    vec4 cubic = vec4(0.0);

    // Tentative collisions of the piecewise-constant majorant: an exponential optical depth tau, spent piece
    // by piece (majorant times the length crossed) until a piece holds the rest. One logarithm per tentative
    // collision, none per macrocell crossed: rays cross many more cells than they collide in.
    UnstructuredHeader mesh;
    if (hasFeature(FEATURE_UNSTRUCTURED_VOLUMES) && v.kind == VOLUME_KIND_UNSTRUCTURED) mesh = unstructuredHeader(v.voxels);
    float tau = -log(1.0 - volumeRandom(rng));
    for (uint chunk = 0u; chunk < VOLUME_STEP_CHUNKS && budget > 0u; ++chunk) {
        uint chunkSteps = min(budget, VOLUME_STEP_CHUNK);
        for (uint steps = 0u; steps < chunkSteps; ++steps, --budget) {
            float tExit = min(t1, min(tNext.x, min(tNext.y, tNext.z)));
            // This step's piece: [t, pieceEnd] under majorant mu; the whole macrocell unless refined.
            float pieceEnd = tExit, mu = majorant;
            vec2 range = vec2(0.0);  // refined: the values the piece's majorant covers
            if (refined) {
                if (t >= voxelExit && voxelExit < tExit) {
                    // Into the next cell (the first of the macrocell: the one holding t).
                    if (voxelExit == -INFINITY)
                        ddaBegin(o, d, inv, stepDir, t, 1.0, ivec3(v.dimX, v.dimY, v.dimZ) - 2, voxelCell, voxelNext);
                    else
                        ddaStep(stepDir, voxelDelta, voxelCell, voxelNext);
                    voxelEntry = t;
                    voxelExit = min(tExit, min(voxelNext.x, min(voxelNext.y, voxelNext.z)));
                    ivec3 loaded = clamp(voxelCell, ivec3(0), ivec3(v.dimX, v.dimY, v.dimZ) - 2);
                    cubic = cellCubic(v, data, loaded, o, d, voxelEntry, voxelExit);
                }
                if (t < voxelExit) {
                    // The rest of the cell, under the cubic's range there.
                    float span = voxelExit - voxelEntry;
                    range = cubicRange(cubic, (t - voxelEntry) / span, (voxelExit - t) / span);
                    mu = extinctionMax(v, data, range.x, range.y) * speed;
                    pieceEnd = voxelExit;
                } else {
                    pieceEnd = t;  // a cell of no length, or the macrocell is done
                    mu = 0.0;
                }
            }
            float segment = mu * (pieceEnd - t);  // optical depth of the majorant to the piece's end
            if (mu > 0.0 && tau < segment) {
                t += tau / mu;
                ++result.collisions;
                // Refined: the cubic's value, kept in the range its majorant was taken over (float rounding
                // may put it a few ulps outside the Bernstein hull).
                vec4 medium = refined ? transferFunction(v, data, clamp(cubicAt(cubic, (t - voxelEntry) / (voxelExit - voxelEntry)),
                                                                        range.x, range.y))
                                      : mediumAt(v, data, o + t * d, mesh);
                float ratio = clamp(medium.w * speed / mu, 0.0, 1.0);
                if (mode == TRACK_RATIO) {
                    result.transmittance *= 1.0 - ratio;
                    // Russian roulette once little light is left: go on with probability T / threshold and
                    // weight threshold (unbiased), so a ray deep in a dense medium stops soon.
                    if (result.transmittance < VOLUME_ROULETTE_BELOW) {
                        if (volumeChance(rng, result.transmittance / VOLUME_ROULETTE_BELOW)) result.transmittance = VOLUME_ROULETTE_BELOW;
                        else result.transmittance = 0.0;
                    }
                    if (result.transmittance <= 0.0) return result;
                } else if (volumeChance(rng, ratio)) {
                    --budget;
                    result.t = t;
                    result.transmittance = 0.0;
                    result.albedo = medium.rgb;
                    return result;
                }
                tau = -log(1.0 - volumeRandom(rng));
                continue;
            }
            tau -= max(segment, 0.0);
            if (pieceEnd < tExit) {  // on within the macrocell, to the next piece or cell
                t = pieceEnd;
                continue;
            }
            // Into the next macrocell with what is left of tau.
            if (tExit >= t1) return result;
            t = tExit;
            ddaStep(stepDir, tDelta, cell, tNext);
            if (any(lessThan(cell, ivec3(0))) || any(greaterThanEqual(cell, macroDims))) return result;
            cellIndex = (uint(cell.z) * v.macroY + uint(cell.y)) * v.macroX + uint(cell.x);
            majorant = data.values[v.majorantOffset + cellIndex] * speed;
            refined = cellByCell && majorant * cellCrossing >= VOLUME_REFINE_DEPTH;
            voxelExit = -INFINITY;
        }
    }
    result.ranOut = true;
    result.t = t;
    return result;
}

TrackResult trackVolume(VolumeRecord v, VolumeDataRef data, vec3 origin, vec3 direction, float tmin, float tmax,
                        uint mode, inout VolumeRng rng, inout uint budget) {
    // cellByCell is set only for linear filtering and at least two voxels per axis; checked again here.
    if (v.cellByCell != 0u && v.filterMode == VOLUME_FILTER_LINEAR && min(v.dimX, min(v.dimY, v.dimZ)) > 1u)
        return trackVolumeMarch(v, data, origin, direction, tmin, tmax, mode, true, rng, budget);
    return trackVolumeMarch(v, data, origin, direction, tmin, tmax, mode, false, rng, budget);
}

// Parking (shared/volume.h): params.volumeParking holds the header and the two pools.
layout(buffer_reference, std430, buffer_reference_align = 16) buffer ParkingRef {
    VolumeParkingHeader header;
    VolumeParked entries[];
};

// This invocation's step budget (the header's; at most VOLUME_STEP_CHUNK * VOLUME_STEP_CHUNKS).
uint volumeStepBudget() {
    return ParkingRef(params.volumeParking).header.stepBudget;
}

// In a resume round: whether invocation gl_GlobalInvocationID.x has a march to resume, and which.
bool parkedMarch(out VolumeParked march) {
    ParkingRef parking = ParkingRef(params.volumeParking);
    uint k = gl_GlobalInvocationID.x;
    uint pool = (params.resumeRound - 1u) & 1u;
    if (k >= min(parking.header.parked[params.resumeRound - 1u].count, parking.header.capacity)) return false;
    march = parking.entries[pool * parking.header.capacity + k];
    return true;
}

// Parks a march for the next round; false when this is the last round or no slot is left.
bool parkMarch(VolumeParked march) {
    ParkingRef parking = ParkingRef(params.volumeParking);
    uint round = params.resumeRound;
    if (round >= parking.header.lastRound) return false;
    uint slot = atomicAdd(parking.header.parked[round].count, 1u);
    if (slot >= parking.header.capacity) return false;
    atomicMax(parking.header.parked[round].groupsX, slot / gl_WorkGroupSize.x + 1u);
    parking.entries[(round & 1u) * parking.header.capacity + slot] = march;
    CountersRef counters = CountersRef(FrameRef(params.frame).frame.counters);
    countVolumeSteps(counters.counters, parkedMarches, 1u);
    return true;
}

#endif

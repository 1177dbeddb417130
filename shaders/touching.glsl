// Touching glass surfaces (docs/render-model-decisions.md, "Touching objects"), collected during
// the closest-hit traversal rather than by the CPU reference's second traversal over
// (t - e, t + e), which costs almost as much as a ray (docs/gpu-design.md, "The ray tree").
//
// Every glass triangle the traversal hits below the nearest hit so far plus e is a *candidate*:
// four slots (xyzw) of an object (| entering << 31) and its nearest crossing t; a slot whose t is
// no longer below that limit is free. Boxes are culled against the same limit, so no candidate is
// missed and the nearest hit is unchanged. At a glass hit, selectTouching keeps the candidates of
// other objects than the hit's: the surfaces the CPU's probe finds, since all lie at or beyond t.
#ifndef VITRUM_TOUCHING_GLSL
#define VITRUM_TOUCHING_GLSL

const float kNoCandidate = 3.4028235e38;  // the largest float: above every limit (tMax starts at 3e38)

// Records that the ray crosses a glass triangle of `object` at t, below `limit` (the nearest hit
// so far plus e). An object keeps its nearest crossing. With four objects in the slots already
// (the nearest hit's and three others), the farthest of the five is dropped and counted in
// `dropped`.
void addTouchingCandidate(inout uvec4 objects, inout vec4 ts, uint object, bool entering, float t, float limit,
                          inout uint dropped) {
    uint tagged = object | (entering ? 0x80000000u : 0u);
    bvec4 valid = lessThan(ts, vec4(limit));
    bvec4 same = bvec4(uvec4(equal(objects & 0x7FFFFFFFu, uvec4(object))) & uvec4(valid));
    if (any(same)) {
        bvec4 nearer = bvec4(uvec4(same) & uvec4(lessThan(vec4(t), ts)));
        ts = mix(ts, vec4(t), nearer);
        objects = mix(objects, uvec4(tagged), nearer);
        return;
    }
    uint slot = !valid.x ? 0u : (!valid.y ? 1u : (!valid.z ? 2u : (!valid.w ? 3u : 4u)));
    if (slot == 4u) {
        dropped += 1u;  // a fourth object touching the nearest hit's: never silently
        float farthest = max(max(ts.x, ts.y), max(ts.z, ts.w));
        if (t >= farthest) return;
        slot = ts.x == farthest ? 0u : (ts.y == farthest ? 1u : (ts.z == farthest ? 2u : 3u));
    }
    bvec4 chosen = equal(uvec4(slot), uvec4(0u, 1u, 2u, 3u));
    ts = mix(ts, vec4(t), chosen);
    objects = mix(objects, uvec4(tagged), chosen);
}

// Puts the pair in (t, object) order.
void orderCandidates(inout float ta, inout uint oa, inout float tb, inout uint ob) {
    bool swap = tb < ta || (tb == ta && (ob & 0x7FFFFFFFu) < (oa & 0x7FFFFFFFu));
    float t = ta;
    uint o = oa;
    ta = swap ? tb : ta;
    oa = swap ? ob : oa;
    tb = swap ? t : tb;
    ob = swap ? o : ob;
}

// The touching surfaces of a glass hit of `hitObject` at `t`, from the candidates: the other
// objects' below t + e, nearest first (ties: the lower object index first), as `uvec4(object |
// entering << 31 for up to 3, how many)`; `farthest` becomes the t of the farthest of them.
uvec4 selectTouching(uvec4 objects, vec4 ts, float limit, uint hitObject, inout float farthest) {
    bvec4 keep = bvec4(uvec4(lessThan(ts, vec4(limit))) &
                       uvec4(notEqual(objects & 0x7FFFFFFFu, uvec4(hitObject))));
    ts = mix(vec4(kNoCandidate), ts, keep);
    // A sorting network of four.
    orderCandidates(ts.x, objects.x, ts.y, objects.y);
    orderCandidates(ts.z, objects.z, ts.w, objects.w);
    orderCandidates(ts.x, objects.x, ts.z, objects.z);
    orderCandidates(ts.y, objects.y, ts.w, objects.w);
    orderCandidates(ts.y, objects.y, ts.z, objects.z);
    uint count = ts.z < kNoCandidate ? 3u : (ts.y < kNoCandidate ? 2u : (ts.x < kNoCandidate ? 1u : 0u));
    if (count > 0u) farthest = max(farthest, count == 3u ? ts.z : (count == 2u ? ts.y : ts.x));
    return uvec4(objects.xyz, count);
}

#endif

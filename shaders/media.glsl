// The medium stack of a ray (render model: "Media: the IOR stack"): the objects it is inside,
// innermost last, and what it crosses at a glass surface.
#ifndef VITRUM_MEDIA_GLSL
#define VITRUM_MEDIA_GLSL

#include "trace_state.glsl"
#include "counters.glsl"
#include "bindings.glsl"
#include "specialization.glsl"
#include "ieee_vector_math.glsl"
#include "optics.glsl"

// The place in the stack of the medium a ray inside `count` > 0 objects is in: the innermost of
// those of the highest priority (render-model-decisions.md, "Overlapping media by priority");
// the innermost, count - 1, where all priorities are equal. Without a loop, as the stack's
// functions below.
uint ruling(uvec4 media, uint count) {
    if (!kMediumPriorities || count == 1u) return count - 1u;
    uint best = 0u;
    int highest = objectPriority(media[0]);
    if (kMediumStackDepth > 1u && count > 1u && objectPriority(media[1]) >= highest) {
        best = 1u;
        highest = objectPriority(media[1]);
    }
    if (kMediumStackDepth > 2u && count > 2u && objectPriority(media[2]) >= highest) {
        best = 2u;
        highest = objectPriority(media[2]);
    }
    if (kMediumStackDepth > 3u && count > 3u && objectPriority(media[3]) >= highest) best = 3u;
    return best;
}

// A ray's wavelength, in origin.w above its depth: from bit 8 the wavelength code, 0 for a white
// ray, 1 + k for wavelength sample k; bit 16 marks a split ray's samples from k on that still wait
// to be traced (render-model-decisions.md, "Dispersion"; shading.glsl's splitIntoWavelengths).
const uint kWavelengthShift = 8u;
const uint kWavelengthsWaiting = 1u << 16u;
uint wavelengthCode(PendingRay r) { return kDispersion ? (floatBitsToUint(r.origin.w) >> kWavelengthShift) & 0xFFu : 0u; }

// An index n_d of object `object`'s glass at the wavelength of a ray of wavelength code `code`:
// n_d + B (1 / lambda^2 - 1 / lambda_d^2), n_d itself for a white ray or a medium that does not
// disperse (render_model/dispersion.h's dispersedIor).
float dispersedIor(float nd, uint object, uint code) {
    if (!kDispersion || code == 0u) return nd;
    float b = objectDispersion(object);
    return b == 0.0 ? nd : nd + b * wavelengthSample(code - 1u).w;
}

// IOR of the medium inside `count` objects in `media`, or of the scene's air, for a ray of
// wavelength code `code`.
float ior(uvec4 media, uint count, uint code) {
    if (!usesMaterial(kMaterialGlass) || count == 0u) return airIor();
    uint object = media[ruling(media, count)];
    return dispersedIor(objectMedium(object).w, object, code);
}

// IOR of the medium a ray is in.
float mediumIor(PendingRay r) { return ior(r.media, mediaCount(r), wavelengthCode(r)); }

vec3 mediumAttenuation(PendingRay r) {
    if (!kAbsorption) return vec3(0.0);
    uint count = mediaCount(r);
    return count == 0u ? vec3(0.0) : objectMedium(r.media[ruling(r.media, count)]).xyz;
}

// Beer-Lambert over the stretch between the un-offset point `start` a new ray leaves from and its
// offset origin. A ray's length in a medium is measured from un-offset point to un-offset point,
// its t from its origin: the ray's weight takes this factor as it is made, so that finishTrace's
// exp(-mu t) completes exp(-mu (t + skipped)) (docs/render-model-decisions.md, "Absorption
// lengths"). Exactly 1 where nothing absorbs.
vec3 skippedTransmittance(PendingRay r, vec3 start) {
    if (!kAbsorption) return vec3(1.0);
    return beerLambert(mediumAttenuation(r), ieeeDot(r.origin.xyz - start, r.direction.xyz));
}

// The medium stack, written without loops: every loop iteration counts against lavapipe's limit.
// The innermost place of `object` in the stack, or `count` where the ray is not inside it.
uint innermostMedium(uvec4 media, uint count, uint object) {
    uint found = count;
    if (count > 0u && media[0] == object) found = 0u;
    if (kMediumStackDepth > 1u && count > 1u && media[1] == object) found = 1u;
    if (kMediumStackDepth > 2u && count > 2u && media[2] == object) found = 2u;
    if (kMediumStackDepth > 3u && count > 3u && media[3] == object) found = 3u;
    return found;
}

// Removes the innermost entry of `object` (normally the top); a ray leaving an object it is not
// inside (an open or badly wound mesh) keeps its stack, and that is counted.
void leaveMedium(inout uvec4 media, inout uint count, uint object) {
    uint found = innermostMedium(media, count, object);
    if (found == count) {
        counters.inconsistentMedia += 1u;
        return;
    }
    if (kMediumStackDepth > 1u && found <= 0u && 1u < count) media[0] = media[1];
    if (kMediumStackDepth > 2u && found <= 1u && 2u < count) media[1] = media[2];
    if (kMediumStackDepth > 3u && found <= 2u && 3u < count) media[2] = media[3];
    count -= 1u;
}

// Entering an object the ray is already inside keeps the stack, and is counted, as leaving one
// it is not inside: a closed mesh cannot be entered twice (where rounding lost a crossing it can
// seem so), and the stack never holds an object twice, so the nesting bounds its depth.
void enterMedium(inout uvec4 media, inout uint count, uint object) {
    if (innermostMedium(media, count, object) != count) {
        counters.inconsistentMedia += 1u;
        return;
    }
    if (count >= kMediumStackDepth) {
        counters.mediumStackOverflows += 1u;
        return;
    }
    media[count] = object;
    count += 1u;
}

// Glass: the ray enters or leaves object k, decided by the geometric normal of the consistently
// wound mesh; the medium stack says what is on the other side. Surfaces of other glass objects
// touching the hit (st.touching) make one interface with it: the ray leaves, then enters, so
// glass touching glass is glass -> glass (lecture: P2 is 1.5 -> 1.5, never 1.5 -> 1 -> 1.5).
// Returns whether the ray enters the hit object; `media` and `count` become the stack beyond.
bool crossGlass(inout uvec4 media, inout uint count) {
    bool entering = ieeeDot(st.ray.direction.xyz, st.hit.geometricNormal) < 0.0;
    uint touchingCount = kTouchingProbe ? st.touching.w : 0u;
    if (touchingCount > 0u) counters.touchingInterfaces += 1u;
    // Leaving first ...
    if (!entering) leaveMedium(media, count, st.hit.object);
    if (touchingCount > 0u && (st.touching.x & 0x80000000u) == 0u) leaveMedium(media, count, st.touching.x);
    if (touchingCount > 1u && (st.touching.y & 0x80000000u) == 0u) leaveMedium(media, count, st.touching.y);
    if (touchingCount > 2u && (st.touching.z & 0x80000000u) == 0u) leaveMedium(media, count, st.touching.z);
    // ... then entering.
    if (entering) enterMedium(media, count, st.hit.object);
    if (touchingCount > 0u && (st.touching.x & 0x80000000u) != 0u) enterMedium(media, count, st.touching.x & 0x7FFFFFFFu);
    if (touchingCount > 1u && (st.touching.y & 0x80000000u) != 0u) enterMedium(media, count, st.touching.y & 0x7FFFFFFFu);
    if (touchingCount > 2u && (st.touching.z & 0x80000000u) != 0u) enterMedium(media, count, st.touching.z & 0x7FFFFFFFu);
    counters.maxMediumDepth = max(counters.maxMediumDepth, count);
    return entering;
}

// What crossing a glass hit's interface tints (render-model-decisions.md, "Glass tint"): the
// product of the tints of the surfaces it crosses, the hit object's first, then the touching
// objects' nearest first, in the CPU reference's order.
vec3 crossingTint() {
    vec3 tint = objectTint(st.hit.object);
    uint touchingCount = kTouchingProbe ? st.touching.w : 0u;
    if (touchingCount > 0u) tint *= objectTint(st.touching.x & 0x7FFFFFFFu);
    if (touchingCount > 1u) tint *= objectTint(st.touching.y & 0x7FFFFFFFu);
    if (touchingCount > 2u) tint *= objectTint(st.touching.z & 0x7FFFFFFFu);
    return tint;
}

// Whether a glass hit on object k's surface, with no touching surfaces, is a false hit: k's
// medium has a lower priority than the medium the ray is in (`media`, `count`: its stack before
// the hit), and the ray enters k, or leaves k from inside it. The ray goes on through it with the
// updated stack, no interface, no depth spent (Schmidt and Budge, "Simple Nested Dielectrics in
// Ray Traced Images", JGT 2002; render-model-decisions.md, "Overlapping media by priority").
bool falseHit(uvec4 media, uint count, uint k, bool entering) {
    if (!kMediumPriorities || count == 0u || (kTouchingProbe && st.touching.w > 0u)) return false;
    if (!entering && innermostMedium(media, count, k) == count) return false;  // not inside k: as without priorities
    return objectPriority(k) < objectPriority(media[ruling(media, count)]);
}

#endif

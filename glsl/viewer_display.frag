#version 460
// The display pass: each framebuffer pixel shows the image pixel under it (nearest, when the
// image is rendered smaller than the window), exposed and tone-mapped into sRGB by shared/tonemap.h,
// the same curve photon-render writes PNG files with. The target is a UNORM format, so the
// sRGB-encoded values are stored as they are.
#extension GL_GOOGLE_include_directive : require
#include "shared/tonemap.h"
#include "glsl/viewer.h"

layout(std430, set = 0, binding = DISPLAY_BINDING_IMAGE) readonly restrict buffer ImageBuffer { vec4 radiance[]; };
layout(std430, set = 0, binding = DISPLAY_BINDING_DOTS) readonly restrict buffer DotBuffer { uint dots[]; };
layout(push_constant) uniform Push { DisplayPush push; };
layout(location = 0) out vec4 color;

void main() {
    uvec2 target = uvec2(gl_FragCoord.xy);
    uint x = min(target.x * push.width / push.targetWidth, push.width - 1u);
    uint y = min(target.y * push.height / push.targetHeight, push.height - 1u);
    uint pixel = y * push.width + x;
    vec3 value;
    if (push.source == DISPLAY_ALBEDO) {
        color = vec4(tonemap(vec3(radiance[DISPLAY_AOV_VEC4S * pixel]), 1.0f, TONEMAP_CLAMP), 1.0f);
        return;
    }
    if (push.source == DISPLAY_NORMAL) {
        color = vec4(0.5f * vec3(radiance[DISPLAY_AOV_VEC4S * pixel + 1u]) + 0.5f, 1.0f);
        return;
    }
    if (push.source == DISPLAY_DEPTH) {
        float depth = radiance[DISPLAY_AOV_VEC4S * pixel].w;
        color = vec4(vec3(depth > 0.0f ? min(push.scale / (1.0f + depth), 1.0f) : 0.0f), 1.0f);
        return;
    }
    if (push.source == DISPLAY_DOTS) {
        value = vec3(float(dots[3u * pixel]), float(dots[3u * pixel + 1u]), float(dots[3u * pixel + 2u])) / DOTS_FIXED_POINT;
    } else {
        value = vec3(radiance[pixel]);
    }
    color = vec4(tonemap(value, push.scale, push.curve), 1.0f);
}

// Textures from PNG or JPEG bytes (stb_image), for the model loaders: the size is checked before
// anything is decoded, sRGB colour is decoded to linear on the host (16 bits a channel, so
// that the shared code samples them with integer arithmetic only), and the result is added to the
// scene's texel buffer.
#pragma once

#include <cstdint>
#include <string>

#include "core/scene/scene.h"

namespace photon {

// How an image's channels are stored: sRGB-encoded colour (base colour, emission) or linear data
// (metallic-roughness, normals).
enum class TextureEncoding { Srgb, Linear };

// Adds the image in `bytes` as a texture; throws InputError "<where>: <reason>" for anything that
// is not a PNG or JPEG image within TEXTURE_SIZE_MAX texels a side.
std::uint32_t addImageTexture(Scene& scene, const std::string& bytes, std::uint32_t wrapS, std::uint32_t wrapT,
                              const std::string& where, TextureEncoding encoding = TextureEncoding::Srgb);

}  // namespace photon

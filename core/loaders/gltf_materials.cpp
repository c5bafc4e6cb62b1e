// The glTF loader's materials (gltf_loader.h): the metallic-roughness model with its extensions as
// Photon's MATERIAL_PBR, its textures (decoded once per encoding, seen through
// KHR_texture_transform), dispersion and the volume's scattering.
#include "core/loaders/gltf_loader.h"

namespace photon::gltf {

void Loader::volumeScatter(const tinygltf::Value& scatter, Material& m) {
    if (!scatter.IsObject() || (m.flags & MATERIAL_FLAG_THIN_WALLED) != 0u || m.attenuation == glm::vec3(0.0f)) {
        return;
    }
    Medium md = homogeneousMedium();
    for (int c = 0; c < 3; ++c) {
        double a = 0.0;
        if (scatter.Has("multiscatterColor") && scatter.Get("multiscatterColor").IsArray() &&
            scatter.Get("multiscatterColor").ArrayLen() == 3 && scatter.Get("multiscatterColor").Get(c).IsNumber()) {
            a = clamp01(scatter.Get("multiscatterColor").Get(c).GetNumberAsDouble());
        }
        double root = 4.09712 + 4.20863 * a - std::sqrt(9.59217 + 41.6808 * a + 17.7126 * a * a);
        double albedo = std::clamp(1.0 - root * root, 0.0, 1.0);
        md.scattering[c] = float(albedo * m.attenuation[c]);
        md.absorption[c] = float((1.0 - albedo) * m.attenuation[c]);
    }
    md.g = float(std::clamp(number(scatter, "scatterAnisotropy", 0.0), -0.99, 0.99));
    m.medium = scene.addMedium(md);
    m.attenuation = glm::vec3(0.0f);
}

float Loader::dispersion(const tinygltf::Value& extension, const std::string& here, std::uint32_t flags) const {
    if (!extension.IsObject() || !extension.Has("dispersion")) {
        return 0.0f;
    }
    const tinygltf::Value& v = extension.Get("dispersion");
    double d = v.IsNumber() ? v.GetNumberAsDouble() : -1.0;
    if (!(d >= 0.0 && d <= 20.0)) {  // an Abbe number of at least 1, as the scene files' abbe
        fail(here + "/extensions/KHR_materials_dispersion/dispersion", "must be a number from 0 to 20 (20 / Abbe number)");
    }
    return (flags & MATERIAL_FLAG_THIN_WALLED) != 0u ? 0.0f : float(d);
}

std::uint32_t Loader::texture(int index, const std::string& where, TextureEncoding encoding) {
    if (index < 0 || std::size_t(index) >= model.textures.size()) {
        fail(where, "texture " + std::to_string(index) + " does not exist");
    }
    std::uint32_t& cached = textures[std::size_t(index)][encoding == TextureEncoding::Srgb ? 0 : 1];
    if (cached != NONE) {
        return cached;
    }
    const tinygltf::Texture& t = model.textures[std::size_t(index)];
    std::string here = at("textures", std::size_t(index));
    if (t.source < 0 || std::size_t(t.source) >= model.images.size()) {
        fail(here, "image " + std::to_string(t.source) + " does not exist");
    }
    auto wrap = [](int mode) {
        return mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE     ? WRAP_CLAMP
               : mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT ? WRAP_MIRRORED_REPEAT
                                                               : WRAP_REPEAT;
    };
    std::uint32_t wrapS = WRAP_REPEAT;
    std::uint32_t wrapT = WRAP_REPEAT;
    if (t.sampler >= 0) {
        if (std::size_t(t.sampler) >= model.samplers.size()) {
            fail(here, "sampler " + std::to_string(t.sampler) + " does not exist");
        }
        wrapS = wrap(model.samplers[std::size_t(t.sampler)].wrapS);
        wrapT = wrap(model.samplers[std::size_t(t.sampler)].wrapT);
    }
    const tinygltf::Image& image = model.images[std::size_t(t.source)];
    std::string bytes(image.image.begin(), image.image.end());
    if (bytes.empty() && !image.uri.empty() && image.uri.rfind("data:", 0) != 0) {
        // tinygltf keeps going past an external image it could not read: read it again for the reason.
        std::string file = namedFile(folderOf(path), image.uri);
        checkNamedFile(path, file, "image", options.paths);
        bytes = read(file, "image");
    }
    cached = addImageTexture(scene, bytes, wrapS, wrapT, path + ": " + at("images", std::size_t(t.source)), encoding);
    return cached;
}

std::uint32_t Loader::textureInfo(int index, int texCoord, const tinygltf::ExtensionMap& extensions, const std::string& where,
                                  TextureEncoding encoding) {
    auto it = extensions.find("KHR_texture_transform");
    if (it != extensions.end() && it->second.IsObject() && it->second.Has("texCoord") &&
        it->second.Get("texCoord").IsInt()) {
        texCoord = it->second.Get("texCoord").Get<int>();
    }
    if (index < 0 || texCoord != 0) {
        return NONE;
    }
    std::uint32_t t = texture(index, where, encoding);
    if (it == extensions.end()) {
        return t;
    }
    const tinygltf::Value& x = it->second;
    auto pair = [&](const char* key, double fallback, int c) {
        if (x.IsObject() && x.Has(key) && x.Get(key).IsArray() && x.Get(key).ArrayLen() == 2 &&
            x.Get(key).Get(c).IsNumber()) {
            return x.Get(key).Get(c).GetNumberAsDouble();
        }
        return fallback;
    };
    double rotation = number(x, "rotation", 0.0);
    double ox = pair("offset", 0.0, 0);
    double oy = pair("offset", 0.0, 1);
    double sx = pair("scale", 1.0, 0);
    double sy = pair("scale", 1.0, 1);
    for (double v : {rotation, ox, oy, sx, sy}) {
        if (!std::isfinite(v) || std::abs(v) > 1e6) {
            fail(where + "/extensions/KHR_texture_transform", "offset, rotation and scale must be finite");
        }
    }
    // (s', t') = T · R · S · (s, t) with R = [cos r, sin r; −sin r, cos r] (the extension's).
    double c = std::cos(rotation);
    double sn = std::sin(rotation);
    glm::vec3 rowS(float(c * sx), float(sn * sy), float(ox));
    glm::vec3 rowT(float(-sn * sx), float(c * sy), float(oy));
    return scene.addTextureView(t, rowS, rowT);
}

std::uint32_t Loader::material(int index, const std::string& where) {
    if (options.material != NONE) {
        return options.material;
    }
    if (index < 0) {
        if (defaultMaterial == NONE) {
            // The glTF default: white, fully metallic and rough (the specification's values).
            defaultMaterial = scene.addMaterial(path + "#default", makePbr(glm::vec3(1.0f), 1.0f, 1.0f));
        }
        return defaultMaterial;
    }
    if (std::size_t(index) >= model.materials.size()) {
        fail(where, "material " + std::to_string(index) + " does not exist");
    }
    if (materials[std::size_t(index)] != NONE) {
        return materials[std::size_t(index)];
    }
    const tinygltf::Material& g = model.materials[std::size_t(index)];
    std::string here = at("materials", std::size_t(index));
    const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
    glm::vec4 base(1.0f);
    for (int c = 0; c < 4 && std::size_t(c) < pbr.baseColorFactor.size(); ++c) {
        base[c] = float(clamp01(pbr.baseColorFactor[std::size_t(c)]));
    }
    Material m = makePbr(glm::vec3(base), float(clamp01(pbr.metallicFactor)), float(clamp01(pbr.roughnessFactor)));
    m.alpha = base.w;
    auto extension = [&](const char* name) {
        auto it = g.extensions.find(name);
        return it == g.extensions.end() ? tinygltf::Value() : it->second;
    };
    m.transmission = float(clamp01(number(extension("KHR_materials_transmission"), "transmissionFactor", 0.0)));
    double ior = number(extension("KHR_materials_ior"), "ior", 1.5);
    if (ior == 0.0) {
        // The ratified schema allows exactly 0 besides ≥ 1: a reflectance of 1 (f0 from ior),
        // which no refracting material has.
        fail(here + "/extensions/KHR_materials_ior/ior", "0 (a reflectance of 1) is not supported: use 1 to 10");
    }
    if (!(ior >= 1.0 && ior <= 10.0)) {
        fail(here + "/extensions/KHR_materials_ior/ior", "must be from 1 to 10");
    }
    m.ior = float(ior);
    // KHR_materials_volume: a body of glass (refracting, absorbing) rather than a thin sheet.
    tinygltf::Value volume = extension("KHR_materials_volume");
    if (!(number(volume, "thicknessFactor", 0.0) > 0.0)) {
        m.flags |= MATERIAL_FLAG_THIN_WALLED;
    }
    double distance = number(volume, "attenuationDistance", HUGE_VAL);
    if (!(distance > 0.0)) {
        fail(here + "/extensions/KHR_materials_volume/attenuationDistance", "must be positive");
    }
    if (std::isfinite(distance) && volume.IsObject() && volume.Has("attenuationColor") &&
        volume.Get("attenuationColor").IsArray() && volume.Get("attenuationColor").ArrayLen() == 3) {
        for (int c = 0; c < 3; ++c) {
            const tinygltf::Value& v = volume.Get("attenuationColor").Get(c);
            double colour = v.IsNumber() ? std::clamp(v.GetNumberAsDouble(), 1e-6, 1.0) : 1.0;
            m.attenuation[c] = float(-std::log(colour) / distance);  // Beer–Lambert: σ = −ln(c)/d
        }
    }
    volumeScatter(extension("KHR_materials_volume_scatter"), m);
    m.dispersion = dispersion(extension("KHR_materials_dispersion"), here, m.flags);
    if (!g.doubleSided) {
        m.flags |= MATERIAL_FLAG_SINGLE_SIDED;
    }
    if (g.alphaMode == "MASK") {
        m.flags |= MATERIAL_FLAG_ALPHA_MASK;
        m.alphaCutoff = float(std::isfinite(g.alphaCutoff) ? std::max(g.alphaCutoff, 0.0) : 0.5);
    } else if (g.alphaMode == "BLEND") {
        m.flags |= MATERIAL_FLAG_ALPHA_BLEND;
    } else if (g.alphaMode != "OPAQUE" && !g.alphaMode.empty()) {
        fail(here + "/alphaMode", "unknown alphaMode '" + g.alphaMode.substr(0, 40) + "'");
    }
    m.albedoTexture = textureInfo(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                  pbr.baseColorTexture.extensions, here + "/pbrMetallicRoughness/baseColorTexture",
                                  TextureEncoding::Srgb);
    m.metallicRoughnessTexture =
        textureInfo(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                    pbr.metallicRoughnessTexture.extensions, here + "/pbrMetallicRoughness/metallicRoughnessTexture",
                    TextureEncoding::Linear);
    m.normalTexture = textureInfo(g.normalTexture.index, g.normalTexture.texCoord, g.normalTexture.extensions,
                                  here + "/normalTexture", TextureEncoding::Linear);
    m.normalScale = std::isfinite(g.normalTexture.scale) ? float(std::clamp(g.normalTexture.scale, -100.0, 100.0)) : 1.0f;
    glm::vec3 emission(0.0f);
    for (int c = 0; c < 3 && std::size_t(c) < g.emissiveFactor.size(); ++c) {
        emission[c] = float(clamp01(g.emissiveFactor[std::size_t(c)]));
    }
    double strength = number(extension("KHR_materials_emissive_strength"), "emissiveStrength", 1.0);
    if (!(strength >= 0.0 && strength < 1e6)) {
        fail(here + "/extensions/KHR_materials_emissive_strength/emissiveStrength", "must be from 0 to 1e6");
    }
    m.emission = emission * float(strength);
    if (!isBlack(m.emission)) {
        m.emissionTexture = textureInfo(g.emissiveTexture.index, g.emissiveTexture.texCoord, g.emissiveTexture.extensions,
                                        here + "/emissiveTexture", TextureEncoding::Srgb);
    }
    std::string name = g.name.empty() ? std::to_string(index) : g.name;
    materials[std::size_t(index)] = scene.addMaterial(path + "#" + name, m);
    return materials[std::size_t(index)];
}

}  // namespace photon::gltf

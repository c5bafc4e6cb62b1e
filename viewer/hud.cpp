// The HUD's widgets. Each widget that changes what is rendered raises the matching request in
// the ViewState; the viewer applies it between frames.
#include "hud.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include <imgui.h>

namespace photon::viewer {
namespace {

// A combo over every value of an enumeration (enumCount), named by toString().
template <typename E>
bool enumCombo(const char* label, E& value) {
    bool changed = false;
    if (ImGui::BeginCombo(label, toString(value))) {
        for (std::uint32_t i = 0; i < enumCount<E>(); ++i) {
            E e = static_cast<E>(i);
            if (ImGui::Selectable(toString(e), e == value)) {
                changed = e != value;
                value = e;
            }
        }
        ImGui::EndCombo();
    }
    return changed;
}

bool sliderUint(const char* label, std::uint32_t& value, std::uint32_t lo, std::uint32_t hi) {
    int v = int(value);
    if (ImGui::SliderInt(label, &v, int(lo), int(hi), "%d", ImGuiSliderFlags_AlwaysClamp) && std::uint32_t(v) != value) {
        value = std::uint32_t(v);
        return true;
    }
    return false;
}

// A count over decades (Dear ImGui 1.86's logarithmic integer slider ignores its minimum). The
// value changes only when the edit is done (the drag released, the typed number entered): every
// frame's value of a drag, or a half-typed number, would each restart the render, or be refused.
bool sliderCount(const char* label, std::uint32_t& value, float lo, float hi) {
    float* editing = ImGui::GetStateStorage()->GetFloatRef(ImGui::GetID(label), -1.0f);
    float v = *editing >= 0.0f ? *editing : float(value);
    ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp | ImGuiSliderFlags_Logarithmic;
    ImGui::SliderFloat(label, &v, lo, hi, "%.0f", flags);
    *editing = ImGui::IsItemActive() ? v : -1.0f;
    if (ImGui::IsItemDeactivatedAfterEdit()) {
        std::uint32_t rounded = std::uint32_t(std::lround(std::clamp(v, lo, hi)));
        if (rounded != value) {
            value = rounded;
            return true;
        }
    }
    return false;
}

// The numbers of the frame before the one the HUD is drawn over: it is built while the GPU runs
// that frame. Lines wrap at the window's edge; below 720 pixels of window the stage times start
// folded, so that the HUD leaves most of the image to see.
void statsSection(const HudInfo& info, bool stagesOpen) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::Text("%s", info.device.c_str());
    ImGui::Text("%.1f fps (%.2f ms)   %s", info.fps, info.frame.loopMs, info.presentMode);
    ImGui::Text("frames accumulated %u", info.accumulated);
    ImGui::Text("%.1f M photons/s (%llu paths a frame)", info.frame.photonsPerSecond * 1e-6,
                static_cast<unsigned long long>(info.stats.emittedPaths()));
    ImGui::Text("stored %s", info.stats.storedList(true).c_str());
    ImGui::PopTextWrapPos();
    ImGui::SetNextItemOpen(stagesOpen, ImGuiCond_FirstUseEver);
    if (ImGui::CollapsingHeader("Stage times") && ImGui::BeginTable("stages", 2, ImGuiTableFlags_SizingFixedFit)) {
        const StageTimes& s = info.frame.stages;
        const PassTimes& p = info.frame.passes;
        std::vector<std::pair<const char*, double>> rows;
        for (const StageInfo& stage : kStages) {
            rows.push_back({stage.name, s[stage.id]});
        }
        rows.insert(rows.end(),
                    {{"photon dots", p.dots}, {"display", p.display}, {"HUD", p.hud}, {"GPU total", s.total() + p.total()}});
        for (const auto& [name, ms] : rows) {
            ImGui::TableNextRow();
            ImGui::TableSetColumnIndex(0);
            ImGui::TextUnformatted(name);
            ImGui::TableSetColumnIndex(1);
            ImGui::Text("%7.2f ms", ms);
        }
        ImGui::EndTable();
    }
}

void renderSection(ViewState& state, const HudInfo& info) {
    RenderSettings& s = state.settings;
    bool changed = false;
    enumCombo("view", state.view);
    changed |= enumCombo("estimator", s.estimator);
    changed |= sliderCount("photons/frame", s.photons, 1000.0f, 4.0e6f);
    float radius = s.radius > 0.0f ? s.radius : info.radius[MAP_GLOBAL];
    if (ImGui::SliderFloat("radius", &radius, 0.001f, 1.0f, "%.4f", ImGuiSliderFlags_Logarithmic)) {
        s.radius = radius;
        changed = true;
    }
    float causticRadius = s.causticRadius > 0.0f ? s.causticRadius : info.radius[MAP_CAUSTIC];
    if (ImGui::SliderFloat("caustic radius", &causticRadius, 0.001f, 1.0f, "%.4f", ImGuiSliderFlags_Logarithmic)) {
        s.causticRadius = causticRadius;
        changed = true;
    }
    changed |= sliderUint("photon depth", s.maxPhotonDepth, 1, 32);
    changed |= sliderUint("eye depth", s.maxEyeDepth, 1, 32);
    changed |= sliderUint("eye splits", s.eyeSplits, 0, EYE_SPLITS_MAX);
    if (s.estimator == Estimator::Knn) {
        changed |= sliderUint("k", s.k, 1, KNN_MAX);
    }
    if (s.estimator == Estimator::Progressive) {
        changed |= ImGui::SliderFloat("alpha", &s.alpha, 0.05f, 0.95f);
    }
    changed |= enumCombo("global light", s.globalMode);
    if (s.globalMode == GlobalMode::FinalGather) {
        changed |= sliderUint("gather rays", s.gatherRays, 1, 64);
    }
    changed |= ImGui::Checkbox("pixel centres (no jitter)", &s.pixelCenter);
    changed |= ImGui::Checkbox("spectral (dispersion)", &s.spectral);
    changed |= enumCombo("denoise", s.denoise);
    changed |= ImGui::Checkbox("keep the history when the camera moves", &s.reproject);
    state.settingsChanged |= changed;

    ImGui::SliderFloat("exposure", &state.exposure, -8.0f, 8.0f, "%.1f stops");
    enumCombo("tone curve", state.tonemap);
    const float scales[] = {1.0f, 0.5f, 0.25f, 0.125f};
    const char* scaleNames[] = {"1", "1/2", "1/4", "1/8"};
    int scale = int(std::find(scales, scales + 4, state.renderScale) - scales) % 4;
    if (ImGui::Combo("render scale", &scale, scaleNames, 4) && scales[scale] != state.renderScale) {
        state.renderScale = scales[scale];
        state.settingsChanged = true;
    }
    if (state.view == DisplayView::Dots) {
        ImGui::Checkbox("hide photons behind surfaces", &state.dotsOcclusion);
        ImGui::SliderFloat("dot brightness", &state.dotsBrightness, 0.01f, 10.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    }
    if (info.windowed && ImGui::Checkbox("vsync", &state.vsync)) {
        state.vsyncChanged = true;
    }
}

// A combo box choosing one of `count` (> 0) things by their names; `selected` kept in range.
template <typename NameOf>
void pickOne(const char* label, std::uint32_t& selected, std::uint32_t count, NameOf nameOf) {
    selected = std::min(selected, count - 1);
    if (ImGui::BeginCombo(label, nameOf(selected).c_str())) {
        for (std::uint32_t i = 0; i < count; ++i) {
            if (ImGui::Selectable(nameOf(i).c_str(), i == selected)) {
                selected = i;
            }
        }
        ImGui::EndCombo();
    }
}

// A participating medium's density (a factor on its coefficients) and g; statistics restart.
void mediaSection(ViewState& state, LightEditor& lights) {
    if (lights.mediumCount() == 0) {
        return;
    }
    pickOne("medium", state.selectedMedium, lights.mediumCount(), [&](std::uint32_t m) { return lights.mediumName(m); });
    float density = lights.mediumDensity(state.selectedMedium);
    if (ImGui::SliderFloat("density", &density, 1e-2f, 1e2f, "%.3f x", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp)) {
        lights.setMediumDensity(state.selectedMedium, density);
        state.lightsChanged = true;
    }
    float g = lights.mediumG(state.selectedMedium);
    if (ImGui::SliderFloat("g (forward > 0)", &g, -0.95f, 0.95f, "%.2f", ImGuiSliderFlags_AlwaysClamp)) {
        lights.setMediumG(state.selectedMedium, g);
        state.lightsChanged = true;
    }
}

void lightSection(ViewState& state, LightEditor& lights) {
    // The environment: its colour (uniform) or intensity (a map), and its turn; statistics restart.
    glm::vec3 radiance = lights.environmentRadiance();
    if (!lights.environmentIsMap()) {
        if (ImGui::ColorEdit3("environment", &radiance.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR)) {
            lights.setEnvironmentRadiance(glm::max(radiance, glm::vec3(0.0f)));
            state.lightsChanged = true;
        }
    } else {
        float intensity = radiance.x;
        if (ImGui::SliderFloat("environment intensity", &intensity, 1e-3f, 1e3f, "%.3f", ImGuiSliderFlags_Logarithmic)) {
            lights.setEnvironmentRadiance(glm::vec3(std::max(intensity, 0.0f)));
            state.lightsChanged = true;
        }
    }
    float turn = lights.environmentTurn();
    if (ImGui::SliderFloat("environment rotation", &turn, -180.0f, 180.0f, "%.0f deg")) {
        lights.setEnvironmentTurn(turn);
        state.lightsChanged = true;
    }
    mediaSection(state, lights);
    if (lights.lightCount() == 0) {
        return;
    }
    pickOne("light", state.selectedLight, lights.lightCount(), [&](std::uint32_t l) { return lights.lightName(l); });
    glm::vec3 p = lights.position(state.selectedLight);
    float speed = 0.002f * lights.loaded().diagonal();
    if (ImGui::DragFloat3("position", &p.x, speed, 0.0f, 0.0f, "%.3f")) {
        lights.setPosition(state.selectedLight, p);
        state.lightsChanged = true;
    }
    ImGui::Checkbox("circle", &state.animateLight);
    ImGui::SameLine();
    if (ImGui::Button("reset lights and media")) {
        lights.reset();
        state.lightsChanged = true;
    }
}

void sceneSection(ViewState& state, const HudInfo& info) {
    static char path[1024] = "";
    ImGui::Text("scene: %s", info.scene.c_str());
    ImGui::InputText("file", path, sizeof(path));
    ImGui::SameLine();
    if (ImGui::Button("open") && path[0] != '\0') {
        state.openScene = path;
    }
    if (ImGui::Button("reload (F5)")) {
        state.reloadScene = true;
    }
    ImGui::SameLine();
    ImGui::Checkbox("reload when the file changes", &state.watchScene);
    if (ImGui::Button("reset camera (R)")) {
        state.resetCamera = true;
    }
    ImGui::SameLine();
    ImGui::SliderFloat("fly speed", &state.flySpeed, 0.01f, 2.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
    if (ImGui::Button("screenshot (F12)")) {
        state.screenshot = true;
    }
    ImGui::SameLine();
    ImGui::Checkbox("with HUD", &state.screenshotHud);
}

void helpSection() {
    ImGui::TextUnformatted(
        "left drag: orbit     right drag: look around\n"
        "middle / shift+left drag: pan     wheel: zoom\n"
        "W A S D: fly   Q E: down, up   shift: faster\n"
        "1-9, 0: final direct global caustic dots grid\n"
        "        albedo normal depth volume\n"
        "arrows, PgUp/PgDn: move the selected light\n"
        "+ -: exposure   V: vsync   H/F1: HUD\n"
        "F5: reload scene (or drop a file)   R: reset camera\n"
        "F12 / P: screenshot   Esc: quit");
}

}  // namespace

HudLayout hudLayout(float windowWidth, float windowHeight) {
    constexpr float kMargin = 8.0f;
    HudLayout layout;
    layout.width = std::min(340.0f, std::max(240.0f, 0.36f * windowWidth));
    layout.maxHeight = std::max(100.0f, windowHeight - 2.0f * kMargin);
    layout.renderOpen = windowHeight >= 720.0f;
    return layout;
}

void buildHud(ViewState& state, LightEditor& lights, const HudInfo& info) {
    ImVec2 display = ImGui::GetIO().DisplaySize;
    HudLayout layout = hudLayout(display.x, display.y);
    ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(layout.width, 0.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(ImVec2(200.0f, 0.0f), ImVec2(display.x, layout.maxHeight));
    ImGui::SetNextWindowBgAlpha(0.8f);
    if (!ImGui::Begin("Photon")) {
        ImGui::End();
        return;
    }
    ImGui::PushItemWidth(-130.0f);  // room for the labels
    statsSection(info, layout.renderOpen);
    ImGui::SetNextItemOpen(layout.renderOpen, ImGuiCond_FirstUseEver);
    if (ImGui::CollapsingHeader("Render")) {
        renderSection(state, info);
    }
    if (ImGui::CollapsingHeader("Lights")) {
        lightSection(state, lights);
    }
    if (ImGui::CollapsingHeader("Scene, camera, screenshot")) {
        sceneSection(state, info);
    }
    if (ImGui::CollapsingHeader("Controls")) {
        helpSection();
    }
    if (!state.message.empty()) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.4f, 1.0f), "%s", state.message.c_str());
        ImGui::PopTextWrapPos();
    }
    ImGui::PopItemWidth();
    ImGui::End();
}

}  // namespace photon::viewer

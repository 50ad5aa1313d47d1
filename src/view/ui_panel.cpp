// The viewer's panel: ImGui 1.86 with its GLFW and Vulkan backends, drawn in
// a render pass of its own over the swapchain image.
#include "sp_types.h"
#include "view/ui_panel.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "soundpaint/result.h"
#include "vk/context.h"
#include "vk/vk_check.h"

namespace sp::view {
namespace {

constexpr const char* kHelp =
    "WASD fly, mouse drag (right button) look, left click place a source, Space pause, N step, B backend, "
    "P pin listener, F1 hide panel, Esc quit";

// display.h has no count of palettes: a new one is added here too.
constexpr std::array<Palette, 3> kPalettes = {Palette::OkabeIto, Palette::HighContrast, Palette::SingleHue};

constexpr std::uint32_t kRayBudgetSliderMax = 100000;
constexpr std::uint32_t kCapSliderMax = 1000;
constexpr std::uint32_t kDefaultCap = 100;  // where the slider starts when "cap" is ticked

// ImGui's backend passes the result of each of its Vulkan calls here, from
// code that cannot unwind an exception (it would leave the backend half
// done): the first failure is kept, and thrown by throw_if_failed once the
// backend has returned. A plain global, as the callback takes no user data;
// there is one panel at a time.
VkResult g_first_failure = VK_SUCCESS;

void note_result(VkResult result) {
  if (result < 0 && g_first_failure == VK_SUCCESS) g_first_failure = result;
}

void throw_if_failed(const char* what) {
  const VkResult result = std::exchange(g_first_failure, VK_SUCCESS);
  if (result != VK_SUCCESS)
    throw Exception(Error{ErrorCode::Vulkan, std::string(what) + " failed: " + vk::result_name(result), result});
}

bool is_srgb(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_A8B8G8R8_SRGB_PACK32:
    case VK_FORMAT_R8G8B8_SRGB:
    case VK_FORMAT_B8G8R8_SRGB:
      return true;
    default:
      return false;
  }
}

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// ImGui's colours are sRGB values and its shader writes them unchanged: into
// an sRGB image they would be encoded a second time and the panel would
// look washed out (its dark background a mid grey). Decoded once here, they
// come out as ImGui means them.
void linearise_style(ImGuiStyle& style) {
  for (ImVec4& color : style.Colors) {
    color.x = srgb_to_linear(color.x);
    color.y = srgb_to_linear(color.y);
    color.z = srgb_to_linear(color.z);
  }
}

// The shape a category is drawn with: the display's override, else the
// built-in's, else a disc (as the simulation's CategoryTable decides).
Shape default_shape(const std::string& category) {
  for (const BuiltinCategory& builtin : builtin_categories())
    if (category == builtin.name) return builtin.shape;
  return Shape::Disc;
}

Shape shape_of(const DisplaySettings& display, const std::string& category) {
  const auto found = display.shapes.find(category);
  return found != display.shapes.end() ? found->second : default_shape(category);
}

}  // namespace

UiPanel::UiPanel(GLFWwindow* window, vk::Context& context, VkFormat color_format, std::uint32_t image_count,
                 const std::vector<VkImageView>& views, VkExtent2D extent)
    // ImGui wants at least two; its buffer sets are reused after this many frames.
    : device_(context.device()), image_count_(std::max(image_count, 2u)) {
  if (ImGui::GetCurrentContext() != nullptr)
    throw Exception(ErrorCode::InvalidArgument, "UiPanel: one at a time (ImGui's context is process-wide)");
  g_first_failure = VK_SUCCESS;

  // The font's combined image sampler is the backend's only descriptor (1.86
  // has no user textures). FREE_DESCRIPTOR_SET as in ImGui's examples, so
  // that a backend which frees its set is valid too.
  const VkDescriptorPoolSize pool_size{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1};
  VkDescriptorPoolCreateInfo pool_info{};
  pool_info.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
  pool_info.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = 1;
  pool_info.pPoolSizes = &pool_size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateDescriptorPool(device_, &pool_info, nullptr, &pool));
  pool_ = vk::UniqueDescriptorPool(device_, pool);

  // LOAD and STORE in COLOR_ATTACHMENT_OPTIMAL: the panel blends over the
  // level already in the image and leaves it where the viewer expects it.
  VkAttachmentDescription color{};
  color.format = color_format;
  color.samples = VK_SAMPLE_COUNT_1_BIT;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  color.initialLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.finalLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  const VkAttachmentReference color_ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = 1;
  subpass.pColorAttachments = &color_ref;
  std::array<VkSubpassDependency, 2> dependencies{};
  // RAW/WAW: the level's colour writes (scene and indicator passes) land
  // before the panel loads the image and blends over it.
  dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[0].dstSubpass = 0;
  dependencies[0].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[0].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  // The panel's writes land before later attachment work on the image;
  // presentation or a copy still has the caller's own barrier.
  dependencies[1].srcSubpass = 0;
  dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[1].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  dependencies[1].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo pass_info{};
  pass_info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
  pass_info.attachmentCount = 1;
  pass_info.pAttachments = &color;
  pass_info.subpassCount = 1;
  pass_info.pSubpasses = &subpass;
  pass_info.dependencyCount = static_cast<std::uint32_t>(dependencies.size());
  pass_info.pDependencies = dependencies.data();
  VkRenderPass render_pass = VK_NULL_HANDLE;
  SP_VK_CHECK(vkCreateRenderPass(device_, &pass_info, nullptr, &render_pass));
  render_pass_ = UniqueRenderPass(device_, render_pass);
  create_framebuffers(views, extent);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  context_ = [] { ImGui::DestroyContext(); };
  ImGuiIO& io = ImGui::GetIO();
  // No imgui.ini in the working directory: the panel starts at the top left
  // every time. Keyboard navigation stays off, so that a click on the panel
  // does not take WASD and the shortcuts away from the viewer.
  io.IniFilename = nullptr;
  ImGui::StyleColorsDark();
  // On a high-DPI screen the font and the spacing grow with the desktop's
  // scale, by whole steps (the built-in font is a pixel font).
  float scale_x = 1.0f, scale_y = 1.0f;
  glfwGetWindowContentScale(window, &scale_x, &scale_y);
  const float scale = std::max(1.0f, std::round(std::max(scale_x, scale_y)));
  if (scale > 1.0f) {
    ImFontConfig font;  // as AddFontDefault() sets it up, larger
    font.SizePixels = 13.0f * scale;
    font.OversampleH = font.OversampleV = 1;
    font.PixelSnapH = true;
    io.Fonts->AddFontDefault(&font);
    ImGui::GetStyle().ScaleAllSizes(scale);
  }
  if (is_srgb(color_format)) linearise_style(ImGui::GetStyle());

  // Chains the window's callbacks installed so far; restores them at the end.
  if (!ImGui_ImplGlfw_InitForVulkan(window, true))
    throw Exception(ErrorCode::Vulkan, "UiPanel: ImGui_ImplGlfw_InitForVulkan failed");
  glfw_backend_ = [] { ImGui_ImplGlfw_Shutdown(); };

  ImGui_ImplVulkan_InitInfo init{};
  init.Instance = context.instance();
  init.PhysicalDevice = context.physical_device();
  init.Device = device_;
  init.QueueFamily = context.queue_family();
  init.Queue = context.queue();
  init.PipelineCache = VK_NULL_HANDLE;
  init.DescriptorPool = pool_.get();
  init.Subpass = 0;
  init.MinImageCount = image_count_;
  init.ImageCount = image_count_;
  init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  init.Allocator = nullptr;
  init.CheckVkResultFn = note_result;
  const bool initialised = ImGui_ImplVulkan_Init(&init, render_pass_.get());
  // Init made its backend data (and whatever objects succeeded) even if a
  // Vulkan call failed: shut down in any case.
  vulkan_backend_ = [] { ImGui_ImplVulkan_Shutdown(); };
  if (!initialised) throw Exception(ErrorCode::Vulkan, "UiPanel: ImGui_ImplVulkan_Init failed");
  throw_if_failed("UiPanel: ImGui_ImplVulkan_Init");
  upload_fonts(context);
}

UiPanel::~UiPanel() = default;

void UiPanel::create_framebuffers(const std::vector<VkImageView>& views, VkExtent2D extent) {
  extent_ = extent;
  framebuffers_.clear();
  framebuffers_.reserve(views.size());
  for (VkImageView view : views) {
    VkFramebufferCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO;
    info.renderPass = render_pass_.get();
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = extent.width;
    info.height = extent.height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    SP_VK_CHECK(vkCreateFramebuffer(device_, &info, nullptr, &framebuffer));
    framebuffers_.emplace_back(device_, framebuffer);
  }
}

// The font atlas goes to the GPU once; the wait says it is done before the
// staging buffer is freed.
void UiPanel::upload_fonts(vk::Context& context) {
  bool recorded = false;
  context.submit_and_wait([&](VkCommandBuffer cmd) { recorded = ImGui_ImplVulkan_CreateFontsTexture(cmd); });
  throw_if_failed("UiPanel: ImGui_ImplVulkan_CreateFontsTexture");
  if (!recorded) throw Exception(ErrorCode::Vulkan, "UiPanel: ImGui_ImplVulkan_CreateFontsTexture failed");
  ImGui_ImplVulkan_DestroyFontUploadObjects();
}

void UiPanel::resize(const std::vector<VkImageView>& views, VkExtent2D extent) {
  create_framebuffers(views, extent);
  // 1.86 only records the new minimum (and drops its buffer sets, after a
  // vkDeviceWaitIdle of its own); it keeps cycling through as many sets as
  // the constructor's image_count.
  const std::uint32_t count = std::max(static_cast<std::uint32_t>(views.size()), 2u);
  if (count != image_count_) {
    ImGui_ImplVulkan_SetMinImageCount(count);
    image_count_ = count;
    throw_if_failed("UiPanel: ImGui_ImplVulkan_SetMinImageCount");
  }
}

PanelActions UiPanel::build(const PanelStats& stats, PanelState& state, const std::vector<std::string>& categories) {
  PanelActions actions;
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  if (visible_) {
    const ImGuiIO& io = ImGui::GetIO();
    const float margin = 8.0f;
    ImGui::SetNextWindowPos(ImVec2(margin, margin), ImGuiCond_FirstUseEver);
    // Never taller than the window: past that it scrolls.
    ImGui::SetNextWindowSizeConstraints(ImVec2(0.0f, 0.0f),
                                        ImVec2(FLT_MAX, std::max(io.DisplaySize.y - 2.0f * margin, 100.0f)));
    if (ImGui::Begin("soundpaint", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
      ImGui::TextUnformatted(stats.device.c_str());
      ImGui::Text("backend: %s", stats.backend.c_str());
      if (!stats.notice.empty()) {
        ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
        ImGui::TextColored(ImVec4(1.0f, 0.7f, 0.3f, 1.0f), "%s", stats.notice.c_str());
        ImGui::PopTextWrapPos();
      }
      ImGui::Separator();
      ImGui::Text("frame       %8.2f ms", stats.frame_ms);
      ImGui::Text("simulation  %8.2f ms", stats.simulation_ms);
      // Its stages, newest frame measured: kernels (GPU) or the worker's step (CPU).
      for (const auto& [stage, ms] : stats.stages) ImGui::Text("  %-10s%8.2f ms", stage.c_str(), ms);
      ImGui::Text("scene       %8.2f ms", stats.scene_ms);
      ImGui::Text("indicators  %8.2f ms", stats.indicators_ms);
      ImGui::Separator();
      ImGui::Text("steps         %llu", static_cast<unsigned long long>(stats.steps));
      if (stats.totals_known) {
        ImGui::Text("casts         %llu", static_cast<unsigned long long>(stats.casts));
        ImGui::Text("rays emitted  %llu", static_cast<unsigned long long>(stats.rays_emitted));
        ImGui::Text("indicators    %llu (%u in the ring)", static_cast<unsigned long long>(stats.indicators),
                    stats.live_indicators);
      }
      ImGui::Text("eye  %.2f %.2f %.2f", static_cast<double>(stats.eye.x), static_cast<double>(stats.eye.y),
                  static_cast<double>(stats.eye.z));
      ImGui::Separator();

      // "###id": the label changes with the state, the widget stays the same.
      if (ImGui::Button(stats.paused ? "Resume###pause" : "Pause###pause")) actions.toggle_pause = true;
      ImGui::SameLine();
      ImGui::BeginDisabled(!stats.paused);  // one step while paused, as N does
      if (ImGui::Button("Step")) actions.single_step = true;
      ImGui::EndDisabled();
      ImGui::SameLine();
      const bool on_gpu = stats.backend == "gpu";
      if (ImGui::Button(on_gpu ? "Switch to CPU###backend" : "Switch to GPU###backend")) actions.switch_backend = true;
      ImGui::SameLine();
      if (ImGui::Button(stats.listener_pinned ? "Follow camera###pin" : "Pin listener###pin"))
        actions.toggle_pin = true;

      // A new budget rebuilds the simulation: reported once, when the
      // slider is let go (or a typed value entered), not every frame of a drag.
      const std::uint32_t min_budget = 0;
      ImGui::SliderScalar("ray budget", ImGuiDataType_U32, &state.ray_budget, &min_budget, &kRayBudgetSliderMax, "%u",
                          ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
      if (ImGui::IsItemDeactivatedAfterEdit()) actions.ray_budget_changed = true;
      if (ImGui::Checkbox("diffraction", &state.diffraction)) actions.diffraction_changed = true;

      if (ImGui::CollapsingHeader("Display")) build_display(state, categories, actions);

      const bool valid = state.category >= 0 && static_cast<std::size_t>(state.category) < categories.size();
      if (ImGui::BeginCombo("Click places",
                            valid ? categories[static_cast<std::size_t>(state.category)].c_str() : "")) {
        for (std::size_t i = 0; i < categories.size(); ++i) {
          const bool selected = valid && static_cast<std::size_t>(state.category) == i;
          ImGui::PushID(static_cast<int>(i));
          if (ImGui::Selectable(categories[i].c_str(), selected)) state.category = static_cast<int>(i);
          if (selected) ImGui::SetItemDefaultFocus();
          ImGui::PopID();
        }
        ImGui::EndCombo();
      }

      ImGui::Separator();
      ImGui::PushTextWrapPos(ImGui::GetFontSize() * 30.0f);
      ImGui::TextUnformatted(kHelp);
      ImGui::PopTextWrapPos();
    }
    ImGui::End();
  }
  ImGui::Render();
  return actions;
}

// Every DisplaySettings field, each edit applied at once (set_display is
// cheap: no simulation is rebuilt).
void UiPanel::build_display(PanelState& state, const std::vector<std::string>& categories, PanelActions& actions) {
  DisplaySettings& display = state.display;
  bool changed = false;

  if (ImGui::BeginCombo("palette", palette_name(display.palette))) {
    for (Palette palette : kPalettes) {
      const bool selected = palette == display.palette;
      if (ImGui::Selectable(palette_name(palette), selected) && !selected) {
        display.palette = palette;
        changed = true;
      }
      if (selected) ImGui::SetItemDefaultFocus();
    }
    ImGui::EndCombo();
  }
  changed |= ImGui::Checkbox("direction", &display.direction);
  ImGui::SameLine();
  changed |= ImGui::Checkbox("outline", &display.outline);
  const ImGuiSliderFlags clamp = ImGuiSliderFlags_AlwaysClamp;
  changed |=
      ImGui::SliderFloat("size scale", &display.size_scale, 0.25f, 4.0f, "%.2f", clamp | ImGuiSliderFlags_Logarithmic);
  changed |= ImGui::SliderFloat("opacity scale", &display.opacity_scale, 0.0f, 2.0f, "%.2f", clamp);
  changed |= ImGui::SliderFloat("min opacity", &display.min_opacity, 0.0f, 1.0f, "%.2f", clamp);

  bool capped = display.max_per_category.has_value();
  if (ImGui::Checkbox("cap", &capped)) {
    display.max_per_category = capped ? std::optional<std::uint32_t>(kDefaultCap) : std::nullopt;
    changed = true;
  }
  ImGui::SameLine();
  std::uint32_t cap = display.max_per_category.value_or(kDefaultCap);
  const std::uint32_t min_cap = 1;
  ImGui::BeginDisabled(!capped);
  if (ImGui::SliderScalar("per category", ImGuiDataType_U32, &cap, &min_cap, &kCapSliderMax, "%u",
                          clamp | ImGuiSliderFlags_Logarithmic) &&
      capped) {
    display.max_per_category = cap;
    changed = true;
  }
  ImGui::EndDisabled();

  // Unset means the front end decides, and the viewer's choice is on.
  bool arrows = display.offscreen_arrows.value_or(true);
  if (ImGui::Checkbox("off-screen arrows", &arrows)) {
    display.offscreen_arrows = arrows;
    changed = true;
  }

  if (ImGui::TreeNode("hide categories")) {
    for (std::size_t i = 0; i < categories.size(); ++i) {
      const std::string& name = categories[i];
      auto& hidden = display.hide_categories;
      const auto found = std::find(hidden.begin(), hidden.end(), name);
      bool hide = found != hidden.end();
      ImGui::PushID(static_cast<int>(i));
      if (ImGui::Checkbox(name.c_str(), &hide)) {
        if (hide) {
          hidden.push_back(name);
        } else {
          hidden.erase(found);
        }
        changed = true;
      }
      ImGui::PopID();
    }
    ImGui::TreePop();
  }

  // An override equal to the category's own shape is dropped, so that the
  // settings say only what differs.
  if (ImGui::TreeNode("shapes")) {
    for (std::size_t i = 0; i < categories.size(); ++i) {
      const std::string& name = categories[i];
      const Shape current = shape_of(display, name);
      ImGui::PushID(static_cast<int>(i));
      if (ImGui::BeginCombo(name.c_str(), shape_name(current))) {
        for (std::uint32_t s = 0; s < kShapeCount; ++s) {
          const Shape shape = static_cast<Shape>(s);
          const bool selected = shape == current;
          if (ImGui::Selectable(shape_name(shape), selected) && !selected) {
            if (shape == default_shape(name)) {
              display.shapes.erase(name);
            } else {
              display.shapes[name] = shape;
            }
            changed = true;
          }
          if (selected) ImGui::SetItemDefaultFocus();
        }
        ImGui::EndCombo();
      }
      ImGui::PopID();
    }
    ImGui::TreePop();
  }

  if (changed) actions.display_changed = true;
}

void UiPanel::record(VkCommandBuffer cmd, std::uint32_t image_index) {
  if (!visible_) return;
  ImDrawData* draw_data = ImGui::GetDrawData();
  if (draw_data == nullptr || draw_data->TotalVtxCount == 0) return;
  if (image_index >= framebuffers_.size())
    throw Exception(ErrorCode::InvalidArgument, "UiPanel::record: image index out of range");
  // ImGui lays out in window coordinates and scales by the window's current
  // framebuffer size, which runs ahead of the swapchain while the window is
  // being resized: scaled to this image instead, its viewport and scissors
  // never leave the framebuffer.
  if (draw_data->DisplaySize.x > 0.0f && draw_data->DisplaySize.y > 0.0f)
    draw_data->FramebufferScale = ImVec2(static_cast<float>(extent_.width) / draw_data->DisplaySize.x,
                                         static_cast<float>(extent_.height) / draw_data->DisplaySize.y);

  VkRenderPassBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
  begin.renderPass = render_pass_.get();
  begin.framebuffer = framebuffers_[image_index].get();
  begin.renderArea = {{0, 0}, extent_};
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(draw_data, cmd);
  vkCmdEndRenderPass(cmd);
  throw_if_failed("UiPanel: ImGui_ImplVulkan_RenderDrawData");
}

bool UiPanel::wants_mouse() const { return visible_ && ImGui::GetIO().WantCaptureMouse; }

bool UiPanel::wants_keyboard() const { return visible_ && ImGui::GetIO().WantCaptureKeyboard; }

}  // namespace sp::view

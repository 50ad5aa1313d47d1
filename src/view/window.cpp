#include "view/window.h"

#include <GLFW/glfw3.h>

#include <glm/glm.hpp>

#include "soundpaint/result.h"

namespace sp::view {
namespace {

std::string glfw_error() {
  const char* text = nullptr;
  glfwGetError(&text);
  return text != nullptr ? text : "unknown GLFW error";
}

}  // namespace

Window::Window(std::uint32_t width, std::uint32_t height, const std::string& title) {
  if (glfwInit() != GLFW_TRUE) {
    throw Exception(ErrorCode::InvalidArgument,
                    "view needs a display, and none could be opened (" + glfw_error() +
                        "); without one, `soundpaint render SCENE --out IMAGE.png` draws the same picture into a file");
  }
  if (glfwVulkanSupported() != GLFW_TRUE) {
    glfwTerminate();
    throw Exception(ErrorCode::Vulkan, "view: GLFW finds no Vulkan loader for windows (" + glfw_error() + ")");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(static_cast<int>(width), static_cast<int>(height), title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string error = glfw_error();
    glfwTerminate();
    throw Exception(ErrorCode::InvalidArgument, "view: cannot open a window (" + error + ")");
  }
  pressed_keys_.assign(GLFW_KEY_LAST + 1, false);
  // Installed before the ImGui panel's, which chains to them.
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, on_key);
  glfwSetMouseButtonCallback(window_, on_mouse_button);
}

void Window::on_key(GLFWwindow* window, int key, int, int action, int) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (self != nullptr && action == GLFW_PRESS && key >= 0 && key <= GLFW_KEY_LAST)
    self->pressed_keys_[static_cast<std::size_t>(key)] = true;
}

void Window::on_mouse_button(GLFWwindow* window, int button, int action, int) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(window));
  if (self != nullptr && action == GLFW_PRESS && button >= 0 && button < 31) self->clicked_buttons_ |= 1 << button;
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::required_instance_extensions() {
  std::uint32_t count = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&count);
  std::vector<std::string> extensions;
  for (std::uint32_t i = 0; i < count; ++i) extensions.emplace_back(names[i]);
  return extensions;
}

VkSurfaceKHR Window::create_surface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  const VkResult result = glfwCreateWindowSurface(instance, window_, nullptr, &surface);
  if (result != VK_SUCCESS)
    throw Exception(Error{ErrorCode::Vulkan,
                          "view: cannot create a Vulkan surface for the window (" + glfw_error() + ")",
                          static_cast<int>(result)});
  return surface;
}

void Window::poll_events() const { glfwPollEvents(); }
bool Window::should_close() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }
void Window::request_close() const { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

VkExtent2D Window::framebuffer_size() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  return {static_cast<std::uint32_t>(std::max(width, 0)), static_cast<std::uint32_t>(std::max(height, 0))};
}

void Window::wait_while_minimised() const {
  for (VkExtent2D size = framebuffer_size(); (size.width == 0 || size.height == 0) && !should_close();
       size = framebuffer_size())
    glfwWaitEvents();
}

void Window::request_size(std::uint32_t width, std::uint32_t height) const {
  glfwSetWindowSize(window_, static_cast<int>(width), static_cast<int>(height));
}

bool Window::key_down(int key) const { return glfwGetKey(window_, key) == GLFW_PRESS; }

bool Window::key_pressed(int key) {
  const bool pressed = pressed_keys_[static_cast<std::size_t>(key)];
  pressed_keys_[static_cast<std::size_t>(key)] = false;
  return pressed;
}

bool Window::mouse_down(int button) const { return glfwGetMouseButton(window_, button) == GLFW_PRESS; }

bool Window::mouse_clicked(int button) {
  const bool clicked = ((clicked_buttons_ >> button) & 1) != 0;
  clicked_buttons_ &= ~(1 << button);
  return clicked;
}

glm::vec2 Window::cursor() const {
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(window_, &x, &y);
  return {static_cast<float>(x), static_cast<float>(y)};
}

}  // namespace sp::view

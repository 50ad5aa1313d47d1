// The viewer's window (GLFW): creation, the Vulkan surface, and the input
// the frame loop polls. GLFW is initialised for the window's lifetime.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <vulkan/vulkan.h>

struct GLFWwindow;

namespace sp::view {

class Window {
 public:
  // Throws sp::Exception(ErrorCode::InvalidArgument) when no display can be
  // opened, with a message that suggests `soundpaint render`.
  Window(std::uint32_t width, std::uint32_t height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  // The instance extensions a surface of this window needs.
  static std::vector<std::string> required_instance_extensions();
  // The surface on `instance`; the caller destroys it before the instance.
  VkSurfaceKHR create_surface(VkInstance instance) const;

  void poll_events() const;
  bool should_close() const;
  void request_close() const;
  // Framebuffer size in pixels; 0 x 0 while minimised.
  VkExtent2D framebuffer_size() const;
  void wait_while_minimised() const;
  // Asks for a new client size (scripted runs and tests: without a window
  // manager the X server grants it at once).
  void request_size(std::uint32_t width, std::uint32_t height) const;

  bool key_down(int key) const;
  // True once per press since the last call, however short the press:
  // GLFW's callbacks record presses between the frame loop's polls (a
  // quick tap or click would fall between two polls of the state).
  bool key_pressed(int key);
  bool mouse_down(int button) const;
  bool mouse_clicked(int button);
  glm::vec2 cursor() const;

 private:
  static void on_key(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void on_mouse_button(GLFWwindow* window, int button, int action, int mods);

  GLFWwindow* window_ = nullptr;
  std::vector<bool> pressed_keys_;  // by GLFW key code: pressed since the last key_pressed()
  int clicked_buttons_ = 0;         // bit per mouse button: pressed since the last mouse_clicked()
};

}  // namespace sp::view

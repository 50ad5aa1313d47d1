// Error reporting for every fallible soundpaint call.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include "soundpaint/export.h"

// Exported from a shared libsoundpaint (export.h).
SP_CPP_API_BEGIN

namespace sp {

enum class ErrorCode {
  InvalidArgument,  // an API argument or command-line option is out of its domain
  InvalidScene,     // a scene file is missing, malformed or unsupported
  InvalidConfig,    // a configuration file or value is malformed or out of range
  Io,               // reading or writing a file failed
  Vulkan,           // a Vulkan call failed or no suitable device exists
  LimitExceeded,    // a request exceeds a device or library limit
};

const char* to_string(ErrorCode code);

// A failure: what kind, and one human-readable line naming the problem
// (for files: the path and what is wrong with it).
struct Error {
  ErrorCode code = ErrorCode::InvalidArgument;
  std::string message;
  int vk_result = 0;  // the VkResult for ErrorCode::Vulkan, else 0
};

// Thrown inside the library; converted to Result<T> at public entry points.
class Exception : public std::runtime_error {
 public:
  explicit Exception(Error error) : std::runtime_error(error.message), error_(std::move(error)) {}
  Exception(ErrorCode code, std::string message) : Exception(Error{code, std::move(message), 0}) {}
  const Error& error() const noexcept { return error_; }

 private:
  Error error_;
};

// Either a value or an Error. Check ok() before value().
template <class T>
class Result {
 public:
  Result(T value) : data_(std::move(value)) {}
  Result(Error error) : data_(std::move(error)) {}

  bool ok() const noexcept { return data_.index() == 0; }
  explicit operator bool() const noexcept { return ok(); }

  T& value() & { return checked(); }
  const T& value() const& { return const_cast<Result*>(this)->checked(); }
  // By value from a temporary, so that `for (auto& x : f().value())` does
  // not iterate a Result that has already gone.
  T value() && { return std::move(checked()); }
  T* operator->() { return &checked(); }
  const T* operator->() const { return &const_cast<Result*>(this)->checked(); }
  T& operator*() { return checked(); }
  const T& operator*() const { return const_cast<Result*>(this)->checked(); }

  const Error& error() const { return std::get<1>(data_); }

 private:
  T& checked() {
    if (!ok()) throw Exception(std::get<1>(data_));
    return std::get<0>(data_);
  }
  std::variant<T, Error> data_;
};

// Runs fn() and turns a thrown sp::Exception (or any std::exception) into an Error.
template <class Fn>
auto capture_errors(Fn&& fn, ErrorCode fallback = ErrorCode::InvalidArgument) -> Result<decltype(fn())> {
  try {
    return fn();
  } catch (const Exception& e) {
    return e.error();
  } catch (const std::bad_alloc&) {
    return Error{ErrorCode::LimitExceeded, "out of memory", 0};
  } catch (const std::exception& e) {
    return Error{fallback, e.what(), 0};
  }
}

}  // namespace sp

SP_CPP_API_END

// Errors as values. Every fallible function returns Result<T> (std::expected) carrying an
// Error whose message names the file, feature or frame and the problem in one line.
// ErrorCode decides the process exit status at the app boundary: kBadInput (a user's file,
// option or stack is wrong) exits 2, everything else exits 1.
#pragma once

#include <exception>
#include <expected>
#include <new>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>

namespace glarecam {

enum class ErrorCode {
  kBadInput,  // malformed or invalid input given by the user: exit status 2
  kIo,        // the system refused a read or write (disk full, read-only, permissions)
  kHardware,  // a device is missing or failed
  kInternal,  // anything else
};

struct Error {
  ErrorCode code = ErrorCode::kInternal;
  std::string message;
};

template <typename T>
using Result = std::expected<T, Error>;
using Status = Result<void>;

inline std::unexpected<Error> fail(ErrorCode code, std::string message) {
  return std::unexpected(Error{code, std::move(message)});
}
inline std::unexpected<Error> badInput(std::string message) {
  return fail(ErrorCode::kBadInput, std::move(message));
}
inline std::unexpected<Error> ioError(std::string message) {
  return fail(ErrorCode::kIo, std::move(message));
}
inline std::unexpected<Error> hardwareError(std::string message) {
  return fail(ErrorCode::kHardware, std::move(message));
}

// Process exit statuses shared by every glarecam executable.
inline constexpr int kExitSuccess = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

inline int exitStatus(const Error& error) {
  return error.code == ErrorCode::kBadInput ? kExitBadInput : kExitFailure;
}

// Inside a catch block: the exception being handled as an Error (out of memory is kIo, anything
// else kInternal), so that an exception from a library becomes a one-line message, not an abort.
inline Error currentExceptionError() {
  try {
    throw;
  } catch (const std::bad_alloc&) {
    return {ErrorCode::kIo, "out of memory"};
  } catch (const std::exception& e) {
    return {ErrorCode::kInternal, std::string("internal error: ") + e.what()};
  } catch (...) {
    return {ErrorCode::kInternal, "internal error"};
  }
}

// Runs `body`, which returns a Result or a Status, turning an exception it throws into its Error
// (currentExceptionError): the one boundary between libraries that throw and errors as values.
template <typename F>
auto catchExceptions(F&& body) -> std::invoke_result_t<F&> {
  try {
    return body();
  } catch (...) {
    return std::unexpected(currentExceptionError());
  }
}

// The text of an errno value ("No such file or directory"), for messages.
inline std::string errnoText(int error) { return std::system_category().message(error); }

// Prefixes the message with context ("frame-03.png: " + message), keeping the code.
inline Error withContext(Error error, const std::string& context) {
  error.message = context + ": " + error.message;
  return error;
}

}  // namespace glarecam

// Inside a function returning Result<...> or Status: evaluates a Result expression, returns its
// error if it failed, otherwise assigns its value to `target`.
#define GLARECAM_ASSIGN(target, expression)                                  \
  do {                                                                       \
    auto glarecam_result_ = (expression);                                    \
    if (!glarecam_result_) return std::unexpected(glarecam_result_.error()); \
    target = std::move(*glarecam_result_);                                   \
  } while (0)

// Same for a Status expression: returns its error if it failed.
#define GLARECAM_CHECK(expression)                                           \
  do {                                                                       \
    auto glarecam_status_ = (expression);                                    \
    if (!glarecam_status_) return std::unexpected(glarecam_status_.error()); \
  } while (0)

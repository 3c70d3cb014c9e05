// The language server's wire: JSON-RPC 2.0 messages framed as LSP 3.17 says ("Content-Length: N\r\n\r\n" then N
// bytes of JSON), read from and written to file descriptors.
//
// The reader never trusts its input: a header block without a usable Content-Length (missing, not a number, larger
// than kMaxBody), an overlong header line or a body that is not JSON is reported as a problem and reading goes on
// with the next header block; a "Content-Length:" in the middle of a garbage line starts a header block again, so a
// message sent after a broken one is still read. Only the end of the input (or a body cut short by it) stops it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace rrflint::server {

using nlohmann::json;

/// JSON-RPC 2.0 and LSP error codes.
enum ErrorCode : int {
  kParseError = -32700,
  kInvalidRequest = -32600,
  kMethodNotFound = -32601,
  kInvalidParams = -32602,
  kInternalError = -32603,
  kServerNotInitialized = -32002,
  kRequestCancelled = -32800,
};

/// The largest body the reader accepts (64 MiB); a longer Content-Length is a bad header.
inline constexpr size_t kMaxBody = size_t{64} << 20;
/// The longest header line kept; the rest of a longer line is skipped.
inline constexpr size_t kMaxHeaderLine = 8192;

/// Reads framed messages from a byte source (a file descriptor, or a buffer in tests and fuzzing).
class MessageReader {
 public:
  /// `source` fills up to `n` bytes at `buf` and returns how many (0 at the end of the input, < 0 on an error).
  using Source = std::function<long(char* buf, size_t n)>;
  explicit MessageReader(Source source) : source_(std::move(source)) {}
  /// A reader of a file descriptor (retries on EINTR).
  static MessageReader of_fd(int fd);

  enum class Status { Message, Problem, End };
  /// The next message: Message with its parsed body in `out` (and `problem` set when a header line was bad but the
  /// Content-Length usable); Problem with `problem` set (a bad header block, a body
  /// that is not JSON: `parse_error` is then true); End at the end of the input, `problem` set when it cut a
  /// message short.
  Status next(json& out, std::string& problem, bool& parse_error);
  /// Bytes read and not handed out yet (the next message may need no more reading).
  bool buffered() const { return pos_ < buf_.size(); }

 private:
  bool fill();                                         // more bytes into buf_; false at the end
  bool read_line(std::string& line, bool& long_line);  // one header line without its terminator; false at the end
  Source source_;
  std::string buf_;
  size_t pos_ = 0;
  bool end_ = false;
};

/// Parses a Content-Length value: digits only (blanks around allowed), at most kMaxBody.
bool parse_length(std::string_view value, size_t& out);

/// Writes one message to a file descriptor (the whole of it, retrying on EINTR). False when the pipe is gone.
bool write_message(int fd, const json& msg);

/// A response, an error response (with optional data), a notification.
json response(const json& id, json result);
json error_response(const json& id, int code, std::string message);
json notification(std::string method, json params);

}  // namespace rrflint::server

// The language server's wire: framing, parsing, writing (protocol.h).
#include "cli/server/protocol.h"
#include "frontend/platform.h"
#include "lint/base/strings.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>

namespace rrflint::server {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// What a header block said.
struct Headers {
  bool any = false;         // at least one line
  bool has_length = false;  // a usable Content-Length
  size_t length = 0;
  std::string problem;  // the first thing wrong with it
};

// Takes one header line into `h`. A line that is no "Name: value" header but holds "Content-Length:" further on
// (a body cut short, then the next message) is read from there.
void take_header(std::string_view line, bool long_line, Headers& h) {
  h.any = true;
  auto bad = [&](std::string why) {
    if (h.problem.empty()) h.problem = std::move(why);
  };
  if (long_line) return bad(fmt::format("a header line longer than {} bytes", kMaxHeaderLine));
  const std::string l = lower(line);
  const size_t at = l.find("content-length:");
  if (at != std::string::npos && at > 0) {
    h = Headers{};  // the garbage belonged to the message before: this block starts afresh
    h.any = true;
    line.remove_prefix(at);
  }
  const size_t colon = line.find(':');
  if (colon == std::string_view::npos || colon == 0) return bad("a header line that is not 'Name: value'");
  const std::string name = lower(trim(line.substr(0, colon)));
  const std::string_view value = trim(line.substr(colon + 1));
  if (name == "content-length") {
    size_t n = 0;
    if (!parse_length(value, n))
      return bad(fmt::format("Content-Length '{}' is not a length of at most {} bytes",
                             std::string(utf8_prefix(value, 40)), kMaxBody));
    h.has_length = true;
    h.length = n;
  }
  // Content-Type and unknown headers are accepted and ignored (the body is JSON in UTF-8 either way).
}

}  // namespace

bool parse_length(std::string_view value, size_t& out) {
  value = trim(value);
  if (value.empty() || value.size() > 12) return false;
  size_t n = 0;
  for (char c : value) {
    if (c < '0' || c > '9') return false;
    n = n * 10 + static_cast<size_t>(c - '0');
  }
  if (n > kMaxBody) return false;
  out = n;
  return true;
}

MessageReader MessageReader::of_fd(int fd) {
  return MessageReader([fd](char* buf, size_t n) -> long {
    for (;;) {
      const ssize_t got = ::read(fd, buf, n);
      if (got < 0 && errno == EINTR) continue;
      return static_cast<long>(got);
    }
  });
}

bool MessageReader::fill() {
  if (end_) return false;
  if (pos_ > 0 && pos_ >= buf_.size() / 2) {
    buf_.erase(0, pos_);
    pos_ = 0;
  }
  char chunk[65536];
  const long got = source_(chunk, sizeof chunk);
  if (got <= 0) {
    end_ = true;
    return false;
  }
  buf_.append(chunk, static_cast<size_t>(got));
  return true;
}

bool MessageReader::read_line(std::string& line, bool& long_line) {
  line.clear();
  long_line = false;
  for (;;) {
    const size_t nl = buf_.find('\n', pos_);
    const size_t stop = nl == std::string::npos ? buf_.size() : nl;
    const size_t room = kMaxHeaderLine + 1 - std::min(line.size(), kMaxHeaderLine + 1);
    line.append(buf_, pos_, std::min(stop - pos_, room));
    if (line.size() > kMaxHeaderLine) {
      long_line = true;
      line.resize(kMaxHeaderLine);
    }
    if (nl != std::string::npos) {
      pos_ = nl + 1;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      return true;
    }
    pos_ = buf_.size();
    if (!fill()) return !line.empty();
  }
}

MessageReader::Status MessageReader::next(json& out, std::string& problem, bool& parse_error) {
  problem.clear();
  parse_error = false;
  Headers h;
  std::string line;
  bool long_line = false;
  for (;;) {
    if (!read_line(line, long_line)) {
      if (h.any) problem = "the input ended inside a header block";
      return Status::End;
    }
    if (line.empty() && !long_line) {
      if (!h.any) continue;  // blank lines between messages
      break;
    }
    take_header(line, long_line, h);
  }
  if (!h.has_length) {
    problem = h.problem.empty() ? "a header block without Content-Length" : h.problem;
    return Status::Problem;
  }
  // A usable length despite a bad line: the body is read (and answered); the caller logs the problem.
  while (buf_.size() - pos_ < h.length)
    if (!fill()) {
      problem = fmt::format("the input ended inside a message body ({} of {} bytes)", buf_.size() - pos_, h.length);
      return Status::End;
    }
  const std::string_view body(buf_.data() + pos_, h.length);
  pos_ += h.length;
  out = json::parse(body, nullptr, /*allow_exceptions=*/false);
  problem = h.problem;
  if (out.is_discarded()) {
    problem = "the message body is not valid JSON";
    parse_error = true;
    return Status::Problem;
  }
  return Status::Message;
}

bool write_message(int fd, const json& msg) {
  const std::string body = msg.dump(-1, ' ', false, json::error_handler_t::replace);
  const std::string data = fmt::format("Content-Length: {}\r\n\r\n", body.size()) + body;
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<size_t>(n);
  }
  return true;
}

json response(const json& id, json result) { return {{"jsonrpc", "2.0"}, {"id", id}, {"result", std::move(result)}}; }

json error_response(const json& id, int code, std::string message) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"error", {{"code", code}, {"message", std::move(message)}}}};
}

json notification(std::string method, json params) {
  return {{"jsonrpc", "2.0"}, {"method", std::move(method)}, {"params", std::move(params)}};
}

}  // namespace rrflint::server

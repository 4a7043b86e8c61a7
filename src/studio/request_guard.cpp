#include "studio/request_guard.h"

#include <sys/random.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fmt/format.h>
#include <stdexcept>

namespace insitu {
namespace {

// Equal strings, in a time that does not depend on where they first differ.
bool same_secret(const std::string& a, const std::string& b) {
  if (a.size() != b.size()) return false;
  unsigned char diff = 0;
  for (std::size_t i = 0; i < a.size(); ++i) diff |= static_cast<unsigned char>(a[i] ^ b[i]);
  return diff == 0;
}

// The value of cookie `name` in a Cookie header ("a=1; b=2"), or "".
std::string cookie_value(const std::string& header, const std::string& name) {
  std::size_t at = 0;
  while (at < header.size()) {
    const std::size_t end = std::min(header.find(';', at), header.size());
    std::size_t begin = at;
    while (begin < end && header[begin] == ' ') ++begin;
    const std::string pair = header.substr(begin, end - begin);
    if (pair.size() > name.size() && pair.compare(0, name.size(), name) == 0 && pair[name.size()] == '=')
      return pair.substr(name.size() + 1);
    at = end + 1;
  }
  return "";
}

// The media type of a Content-Type value, without its parameters ("application/json; charset=utf-8").
std::string media_type(const std::string& content_type) {
  std::string type = content_type.substr(0, content_type.find(';'));
  while (!type.empty() && type.back() == ' ') type.pop_back();
  for (char& ch : type) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  return type;
}

bool changes_state(const std::string& method) { return method != "GET" && method != "HEAD"; }

}  // namespace

std::string random_token() {
  unsigned char bytes[16];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw std::runtime_error(std::string("getrandom: ") + std::strerror(errno));
    got += std::size_t(n);
  }
  std::string hex;
  for (unsigned char b : bytes) hex += fmt::format("{:02x}", b);
  return hex;
}

std::string token_cookie_name(int port) { return fmt::format("insitu_studio_{}", port); }

std::string token_cookie(const StudioGuard& guard) {
  return fmt::format("{}={}; Path=/; HttpOnly; SameSite=Strict", token_cookie_name(guard.port), guard.token);
}

GuardVerdict judge_request(const StudioGuard& guard, const RequestHeaders& r) {
  const std::string ip = fmt::format("127.0.0.1:{}", guard.port), name = fmt::format("localhost:{}", guard.port);
  if (r.host != ip && r.host != name)
    return {403, fmt::format("Host '{}' is not this studio's ({} or {}): a page on another site cannot use it", r.host,
                             ip, name)};
  const std::string scheme_token = "token ";
  const bool by_header = r.authorization.compare(0, scheme_token.size(), scheme_token) == 0 &&
                         same_secret(r.authorization.substr(scheme_token.size()), guard.token);
  const bool by_param = !r.token_param.empty() && same_secret(r.token_param, guard.token);
  const std::string cookie = cookie_value(r.cookie, token_cookie_name(guard.port));
  const bool by_cookie = !cookie.empty() && same_secret(cookie, guard.token);
  if (!by_header && !by_param && !by_cookie)
    return {403, fmt::format("no valid token: open the address insitu studio printed (http://{}/?token=...)", ip)};
  if (changes_state(r.method)) {
    if (r.origin != "http://" + ip && r.origin != "http://" + name)
      return {403, fmt::format("Origin '{}' is not this studio's page: a {} must come from http://{}/", r.origin,
                               r.method, ip)};
    if (media_type(r.content_type) != "application/json")
      return {415,
              fmt::format("a {} must be sent as Content-Type: application/json (not '{}')", r.method, r.content_type)};
  }
  return {0, "", by_param};
}

}  // namespace insitu

// A copy of the demo scene with the studio serving it on a free port, for the studio's tests.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <thread>

#include "core/json_reader.h"
#include "studio/studio_server.h"
#include "test_util.h"
// Last: glibc's <resolv.h>, which httplib.h includes, defines _res as a macro that breaks Eigen.
#include <httplib.h>

namespace insitu::test {

// The demo scene copied into dir/demo, and a server over it on a free port.
class StudioFixture {
 public:
  explicit StudioFixture(const TempDir& dir, const std::string& points_text = "") : folder_(dir.path() / "demo") {
    std::filesystem::copy(std::filesystem::path(test::source_dir()) / "scenes/demo", folder_,
                          std::filesystem::copy_options::recursive);
    // Without the outputs the README's first command leaves in the source tree: a test of what the
    // studio writes must not find them there already.
    std::filesystem::remove_all(folder_ / "out");
    if (!points_text.empty()) std::ofstream(folder_ / "points.json") << points_text;
    server_ = std::make_unique<StudioServer>(StudioOptions{(folder_ / "scene.json").string(), 0});
    port_ = server_->bind();
    thread_ = std::thread([this] { server_->run(); });
  }
  ~StudioFixture() {
    server_->stop();
    thread_.join();
  }
  // A client that speaks as the page does: the launch's token, and the page's own Origin (every
  // request but GET and HEAD needs it, request_guard.h).
  httplib::Client client() const {
    httplib::Client c = bare_client();
    c.set_default_headers({{"Authorization", "token " + server_->token()}, {"Origin", origin()}});
    return c;
  }
  // A client with no token and no Origin: what another web site, or another program, has.
  httplib::Client bare_client() const {
    httplib::Client c("127.0.0.1", port_);
    c.set_url_encode(false);  // paths go out exactly as written, "%2e%2e" included
    // A hang guard, not a timing test: httplib's default of 5 s is shorter than GET /api/shots
    // (the demo's cube assembled) takes under AddressSanitizer beside another test shard; CI's
    // sanitized suite failed there with no reply (2026-11-25).
    c.set_read_timeout(300, 0);
    c.set_write_timeout(300, 0);
    return c;
  }
  const std::filesystem::path& folder() const { return folder_; }
  int port() const { return port_; }
  const std::string& token() const { return server_->token(); }
  std::string origin() const { return "http://127.0.0.1:" + std::to_string(port_); }
  StudioServer& server() { return *server_; }

 private:
  std::filesystem::path folder_;
  std::unique_ptr<StudioServer> server_;
  int port_ = 0;
  std::thread thread_;
};

// A file's bytes (the scene file an edit rewrote).
inline std::string text_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A POST of `body` as JSON; the reply's status and body.
inline std::pair<int, json> post(httplib::Client c, const std::string& path, const json& body) {
  const auto r = c.Post(path.c_str(), body.dump(), "application/json");
  if (!r) {
    ADD_FAILURE() << path << ": no reply (" << httplib::to_string(r.error()) << ")";
    return {0, json()};
  }
  return {r->status, json::parse(r->body)};
}

inline json get_json(const httplib::Client& c_in, const std::string& path) {
  httplib::Client& c = const_cast<httplib::Client&>(c_in);
  const auto r = c.Get(path.c_str());
  if (!r) {
    ADD_FAILURE() << path << ": no reply (" << httplib::to_string(r.error()) << ")";
    return json();
  }
  EXPECT_EQ(r->status, 200) << path << ": " << r->body;
  return json::parse(r->body);
}

}  // namespace insitu::test

// Who may use the studio (issue 46, src/studio/request_guard.h): each rule alone, then the server
// attacked as a page on another site, or another program, would attack it.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fmt/format.h>
#include <set>
#include <thread>

#include "cli_util.h"
#include "studio/request_guard.h"
#include "studio_fixture.h"
#include "test_util.h"

namespace insitu {
namespace {

using test::StudioFixture;
using test::TempDir;
namespace fs = std::filesystem;

const StudioGuard kGuard{"0123456789abcdef0123456789abcdef", 8123};

// What the studio's own page sends: its Host, its cookie, its Origin and JSON.
RequestHeaders page_request(const std::string& method) {
  return {method,
          "127.0.0.1:8123",
          method == "GET" ? "" : "http://127.0.0.1:8123",
          "application/json",
          "",
          "other=1; insitu_studio_8123=0123456789abcdef0123456789abcdef",
          ""};
}

TEST(StudioGuard, ThePagesOwnRequestsPass) {
  for (const char* method : {"GET", "HEAD", "POST", "PUT"})
    EXPECT_EQ(judge_request(kGuard, page_request(method)).status, 0) << method;
  RequestHeaders r = page_request("POST");
  r.host = "localhost:8123", r.origin = "http://localhost:8123", r.content_type = "application/json; charset=utf-8";
  EXPECT_EQ(judge_request(kGuard, r).status, 0);
}

TEST(StudioGuard, AForeignHostIsRefusedWhateverElseItCarries) {
  for (const char* host : {"evil.example:8123", "127.0.0.1:8124", "127.0.0.1", "localhost", "",
                           "127.0.0.1:8123.evil.example", "[::1]:8123"}) {
    RequestHeaders r = page_request("GET");
    r.host = host;
    const GuardVerdict v = judge_request(kGuard, r);
    EXPECT_EQ(v.status, 403) << host;
    EXPECT_NE(v.what.find("Host"), std::string::npos) << v.what;
  }
}

TEST(StudioGuard, EveryRequestNeedsTheToken) {
  RequestHeaders r = page_request("GET");
  r.cookie = "";
  EXPECT_EQ(judge_request(kGuard, r).status, 403);
  for (const char* cookie : {"insitu_studio_8123=0123456789abcdef0123456789abcdee",  // one digit off
                             "insitu_studio_8124=0123456789abcdef0123456789abcdef",  // another studio's cookie
                             "xinsitu_studio_8123=0123456789abcdef0123456789abcdef",
                             "insitu_studio_8123=", "insitu_studio_8123=0123456789abcdef0123456789abcdef0"}) {
    r.cookie = cookie;
    EXPECT_EQ(judge_request(kGuard, r).status, 403) << cookie;
  }
  r.cookie = "";
  r.authorization = "token 0123456789abcdef0123456789abcdef";
  EXPECT_EQ(judge_request(kGuard, r).status, 0);
  EXPECT_FALSE(judge_request(kGuard, r).set_cookie);
  r.authorization = "Bearer 0123456789abcdef0123456789abcdef";
  EXPECT_EQ(judge_request(kGuard, r).status, 403);
  r.authorization = "", r.token_param = kGuard.token;
  const GuardVerdict by_url = judge_request(kGuard, r);
  EXPECT_EQ(by_url.status, 0);
  EXPECT_TRUE(by_url.set_cookie);  // the page opened from the printed address gets its cookie
  r.token_param = "0";
  EXPECT_EQ(judge_request(kGuard, r).status, 403);
}

TEST(StudioGuard, AChangeNeedsThePagesOriginAndJson) {
  for (const char* origin : {"", "null", "http://evil.example", "http://127.0.0.1:8124", "https://127.0.0.1:8123",
                             "http://127.0.0.1:8123/"}) {
    RequestHeaders r = page_request("POST");
    r.origin = origin;
    EXPECT_EQ(judge_request(kGuard, r).status, 403) << origin;
  }
  // What an HTML form can send, and a body with no type.
  for (const char* type : {"text/plain", "application/x-www-form-urlencoded", "multipart/form-data; boundary=x", "",
                           "application/jsonx", "text/json"}) {
    RequestHeaders r = page_request("PUT");
    r.content_type = type;
    EXPECT_EQ(judge_request(kGuard, r).status, 415) << type;
    r.method = "GET";  // a read needs neither
    EXPECT_EQ(judge_request(kGuard, r).status, 0) << type;
  }
  RequestHeaders preflight = page_request("OPTIONS");
  preflight.cookie = "", preflight.origin = "http://evil.example";
  EXPECT_EQ(judge_request(kGuard, preflight).status, 403);  // no CORS: the preflight is refused
}

TEST(StudioGuard, TokensAreFreshAndHex) {
  std::set<std::string> seen;
  for (int i = 0; i < 64; ++i) {
    const std::string t = random_token();
    ASSERT_EQ(t.size(), 32u);
    EXPECT_EQ(t.find_first_not_of("0123456789abcdef"), std::string::npos) << t;
    seen.insert(t);
  }
  EXPECT_EQ(seen.size(), 64u);
  EXPECT_EQ(token_cookie(kGuard),
            "insitu_studio_8123=0123456789abcdef0123456789abcdef; Path=/; HttpOnly; SameSite=Strict");
}

// The reply's status, or 0 with the failure noted.
int status_of(const httplib::Result& r, const std::string& what) {
  if (!r) {
    ADD_FAILURE() << what << ": no reply (" << httplib::to_string(r.error()) << ")";
    return 0;
  }
  return r->status;
}

TEST(StudioGuard, ServesNothingToAForeignHostOrWithoutTheToken) {
  TempDir dir;
  StudioFixture studio(dir);
  auto good = studio.client();
  auto bare = studio.bare_client();
  const httplib::Headers rebound = {{"Host", "evil.example:" + std::to_string(studio.port())},
                                    {"Authorization", "token " + studio.token()}};
  for (const char* path : {"/", "/studio.js", "/api/state", "/api/photo.png", "/files/points.json", "/api/shots",
                           "/api/shots/stitched.png", "/api/render"}) {
    EXPECT_EQ(status_of(good.Get(path), path), 200) << path;
    const auto foreign = good.Get(path, rebound);
    EXPECT_EQ(status_of(foreign, path), 403) << path;
    if (foreign) {
      EXPECT_EQ(foreign->body.find("PNG"), std::string::npos);  // not a byte of the photo
    }
    EXPECT_EQ(status_of(bare.Get(path), path), 403) << path;
  }
  // The printed address opens the page and hands it the cookie, which is then enough alone.
  const auto opened = bare.Get(("/?token=" + studio.token()).c_str());
  ASSERT_EQ(status_of(opened, "/?token="), 200);
  const std::string cookie = opened->get_header_value("Set-Cookie");
  EXPECT_NE(cookie.find("HttpOnly"), std::string::npos) << cookie;
  EXPECT_NE(cookie.find("SameSite=Strict"), std::string::npos) << cookie;
  EXPECT_EQ(status_of(bare.Get("/api/photo.png", {{"Cookie", cookie.substr(0, cookie.find(';'))}}), "cookie"), 200);
}

TEST(StudioGuard, ACrossSiteRequestChangesNothing) {
  TempDir dir;
  StudioFixture studio(dir);
  const std::string points_before = test::text_of(studio.folder() / "points.json");
  const std::string scene_before = test::text_of(studio.folder() / "scene.json");
  const std::string version = test::get_json(studio.client(), "/api/state")["version"];
  auto good = studio.client();
  const std::string token = "token " + studio.token();
  const std::string points = json{{"version", version}, {"points", json::array()}}.dump();
  // A form on another site (no cookie: SameSite), the same with the token somehow known, and a
  // fetch() whose preflight was skipped: from another Origin, or as a form's text/plain.
  const std::vector<httplib::Headers> attacks = {
      {{"Origin", "http://evil.example"}},
      {{"Origin", "http://evil.example"}, {"Authorization", token}},
      {{"Origin", "null"}, {"Authorization", token}},
      {{"Authorization", token}},  // no Origin at all
  };
  httplib::Client bare = studio.bare_client();
  for (const auto& headers : attacks) {
    for (const char* path : {"/api/render", "/api/render/stop", "/api/render/save", "/api/shots", "/api/references"})
      EXPECT_EQ(status_of(bare.Post(path, headers, "{\"spp\": 1048576}", "application/json"), path), 403) << path;
    EXPECT_EQ(status_of(bare.Put("/api/points", headers, points, "application/json"), "PUT"), 403);
  }
  for (const char* type : {"text/plain", "application/x-www-form-urlencoded", "multipart/form-data; boundary=b"}) {
    EXPECT_EQ(status_of(good.Post("/api/render", "{\"spp\": 1048576}", type), type), 415) << type;
    EXPECT_EQ(status_of(good.Post("/api/render/save", "{}", type), type), 415) << type;
    EXPECT_EQ(status_of(good.Put("/api/points", points, type), type), 415) << type;
  }
  EXPECT_EQ(test::get_json(studio.client(), "/api/render")["state"], "idle");  // no render started
  EXPECT_EQ(test::text_of(studio.folder() / "points.json"), points_before);
  EXPECT_EQ(test::text_of(studio.folder() / "scene.json"), scene_before);
  EXPECT_FALSE(fs::exists(studio.folder() / "out"));
}

TEST(StudioGuard, EveryReplyForbidsFramingAndRefusalsExplainThemselves) {
  TempDir dir;
  StudioFixture studio(dir);
  auto good = studio.client();
  auto bare = studio.bare_client();
  for (const auto& r : {good.Get("/"), good.Get("/api/state"), bare.Get("/"), good.Get("/nonexistent")}) {
    ASSERT_TRUE(r);
    EXPECT_EQ(r->get_header_value("X-Frame-Options"), "DENY");
    EXPECT_NE(r->get_header_value("Content-Security-Policy").find("frame-ancestors 'none'"), std::string::npos);
    EXPECT_EQ(r->get_header_value("X-Content-Type-Options"), "nosniff");
    EXPECT_FALSE(r->has_header("Access-Control-Allow-Origin"));
  }
  const auto refused = bare.Get("/api/state");
  ASSERT_TRUE(refused);
  EXPECT_NE(json::parse(refused->body)["error"].get<std::string>().find("token"), std::string::npos) << refused->body;
}

TEST(StudioGuard, BadBodiesAreA400WithAMessage) {
  TempDir dir;
  StudioFixture studio(dir);
  auto c = studio.client();
  // Not UTF-8 (a lone continuation byte, an overlong form, a truncated sequence), and bodies that
  // are JSON but not an object.
  for (const std::string& body :
       {std::string("{\"spp\": \"\x80\"}"), std::string("{\"\xc0\xaf\": 1}"), std::string("\xe2\x82"),
        std::string("[1, 2]"), std::string("\"path\""), std::string("16"), std::string("null")}) {
    const auto r = c.Post("/api/render", body, "application/json");
    ASSERT_EQ(status_of(r, body), 400) << body;
    const json reply = json::parse(r->body);  // valid JSON, with a message
    EXPECT_FALSE(reply["error"].get<std::string>().empty());
  }
  EXPECT_EQ(test::get_json(studio.client(), "/api/render")["state"], "idle");
}

TEST(StudioGuard, ASecondStudioOnThePortIsAOneLineError) {
  TempDir dir;
  StudioFixture studio(dir);
  StudioServer second(StudioOptions{(studio.folder() / "scene.json").string(), studio.port()});
  EXPECT_THROW(second.bind(), InputError);
  const auto run = test::run_insitu(
      dir, fmt::format("studio {} --port {}", (studio.folder() / "scene.json").string(), studio.port()));
  test::expect_one_line_error(run, fmt::format("--port {}", studio.port()));
  EXPECT_EQ(run.out, "");  // no address printed as if all were well
}

// A connection to the studio that sends `bytes` (maybe none) and then nothing.
int stalled_connection(int port, const std::string& bytes) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(std::uint16_t(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  EXPECT_EQ(connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr), 0);
  if (!bytes.empty()) {
    EXPECT_EQ(send(fd, bytes.data(), bytes.size(), 0), ssize_t(bytes.size()));
  }
  return fd;
}

// Open: the server has not closed it (a read finds no end of stream).
bool still_open(int fd) {
  char c;
  const ssize_t n = recv(fd, &c, 1, MSG_DONTWAIT);
  return n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK);
}

// Stalled connections must not hold every thread. Each sends a request's first line and then one
// byte of a header every 0.5 s (a slow client, never timed out); a request is answered while all
// of them are still open. Before, 8 such connections held all 8 of httplib's threads and every
// other request waited for them to end.
TEST(StudioGuard, StalledConnectionsDoNotStallThePage) {
  TempDir dir;
  StudioFixture studio(dir);
  std::vector<int> stalled;
  for (int i = 0; i < 16; ++i)
    stalled.push_back(stalled_connection(studio.port(), "GET /api/state HTTP/1.1\r\nX-Slow: "));
  std::atomic<bool> trickling{true};
  std::thread trickle([&] {
    while (trickling) {
      for (int fd : stalled) send(fd, "a", 1, MSG_NOSIGNAL);
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
  });
  auto c = studio.client();
  c.set_read_timeout(60, 0);  // a hang guard: before, the reply never came while they trickled
  const auto r = c.Get("/api/state");
  int open = 0;
  for (int fd : stalled) open += still_open(fd);
  trickling = false;
  trickle.join();
  for (int fd : stalled) close(fd);
  ASSERT_EQ(status_of(r, "/api/state"), 200);
  EXPECT_EQ(open, 16);
}

}  // namespace
}  // namespace insitu

// Who may use the studio. It listens on 127.0.0.1, and every web page the user opens
// can send requests there too; it reads the customer's photo and writes files. So, as Jupyter does:
//  1. Host must be 127.0.0.1:PORT or localhost:PORT. A page on another site whose name resolves to
//     127.0.0.1 (DNS rebinding) sends its own name as Host, and is refused.
//  2. Every request carries the launch's token (128 bits from getrandom(2), printed in the URL):
//     as ?token=, as "Authorization: token T", or as the cookie the page receives when it is
//     opened with ?token= (HttpOnly, SameSite=Strict: no other site's request carries it).
//  3. A request that can change anything (every method but GET and HEAD) carries the page's own
//     Origin and "Content-Type: application/json". An HTML form on another site can send
//     neither; fetch() from another origin with that type needs a CORS preflight, which is
//     refused like any request without the token.
// A pure function of the request's headers, so that each rule is tested alone
// (tests/studio_guard_test.cpp); studio_server.cpp applies it before any route, and before a
// request's body is read.
#pragma once
#include <string>

namespace insitu {

struct StudioGuard {
  std::string token;  // 32 hex digits
  int port = 0;
};

// The parts of a request the guard reads ("" where absent).
struct RequestHeaders {
  std::string method, host, origin, content_type, authorization, cookie, token_param;
};

struct GuardVerdict {
  int status = 0;           // 0: allowed; else the HTTP status of the refusal (403, 415)
  std::string what;         // why, in one line
  bool set_cookie = false;  // allowed by ?token=: the reply sets the page's cookie
};

// A fresh token: 16 bytes from getrandom(2), as 32 lower-case hex digits.
std::string random_token();

// The cookie's name, with the port: a browser sends a host's cookies to all its ports, and two
// studios on two ports have two tokens.
std::string token_cookie_name(int port);
// The Set-Cookie header's value that hands the page the token.
std::string token_cookie(const StudioGuard& guard);

GuardVerdict judge_request(const StudioGuard& guard, const RequestHeaders& request);

}  // namespace insitu

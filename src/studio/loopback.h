#pragma once
// Which addresses and Host headers count as "this machine only". The studio binds the loopback
// interface unless told otherwise (--allow-remote), and then also answers only requests whose
// Host header names the loopback: a web page elsewhere that points its own DNS name at 127.0.0.1
// (DNS rebinding) cannot read the studio's answers through the user's browser.
#include <string>
#include <string_view>

namespace inet::studio {

/// Is `host` loopback only: "localhost", an IPv4 address in 127.0.0.0/8 or "::1"? Another name
/// is resolved (getaddrinfo) and counts when every address it has is loopback; "0.0.0.0", "::"
/// (every interface) and names that do not resolve do not count.
bool isLoopbackHost(const std::string& host);

/// The host part of a Host header ("localhost:8080" -> "localhost", "[::1]:80" -> "::1").
std::string hostHeaderName(std::string_view host_header);

/// Does a Host header name the loopback by a literal or "localhost" (no DNS lookup: the point
/// is to refuse names an attacker controls)? An empty header does not.
bool isLoopbackHostHeader(std::string_view host_header);

/// Is the IPv4 or IPv6 literal `ip` a loopback address (no DNS lookup)?
bool isLoopbackLiteral(const std::string& ip);

}  // namespace inet::studio

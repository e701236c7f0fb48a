#include "studio/loopback.h"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <algorithm>
#include <cctype>
#include <cstring>

namespace inet::studio {

namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool isLocalhostName(const std::string& name) {
  // RFC 6761: "localhost" and names below it resolve to the loopback
  const std::string n = lower(name);
  return n == "localhost" || n == "localhost." ||
         (n.size() > 10 && n.compare(n.size() - 10, 10, ".localhost") == 0);
}

}  // namespace

bool isLoopbackLiteral(const std::string& ip) {
  in_addr v4{};
  if (inet_pton(AF_INET, ip.c_str(), &v4) == 1) return (ntohl(v4.s_addr) >> 24) == 127;
  in6_addr v6{};
  if (inet_pton(AF_INET6, ip.c_str(), &v6) == 1) {
    if (IN6_IS_ADDR_LOOPBACK(&v6)) return true;
    if (IN6_IS_ADDR_V4MAPPED(&v6)) return v6.s6_addr[12] == 127;  // ::ffff:127.x.y.z
  }
  return false;
}

bool isLoopbackHost(const std::string& host) {
  if (host.empty()) return false;
  if (isLocalhostName(host) || isLoopbackLiteral(host)) return true;
  in_addr v4{};
  in6_addr v6{};
  if (inet_pton(AF_INET, host.c_str(), &v4) == 1 || inet_pton(AF_INET6, host.c_str(), &v6) == 1)
    return false;  // a literal that is not loopback (0.0.0.0, ::, a LAN address)
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* res = nullptr;
  if (getaddrinfo(host.c_str(), nullptr, &hints, &res) != 0 || res == nullptr) return false;
  bool all = true;
  char buf[INET6_ADDRSTRLEN];
  for (addrinfo* a = res; a != nullptr && all; a = a->ai_next) {
    const void* addr =
        a->ai_family == AF_INET
            ? static_cast<const void*>(&reinterpret_cast<sockaddr_in*>(a->ai_addr)->sin_addr)
            : static_cast<const void*>(&reinterpret_cast<sockaddr_in6*>(a->ai_addr)->sin6_addr);
    all = inet_ntop(a->ai_family, addr, buf, sizeof buf) != nullptr && isLoopbackLiteral(buf);
  }
  freeaddrinfo(res);
  return all;
}

std::string hostHeaderName(std::string_view h) {
  if (!h.empty() && h.front() == '[') {  // [v6]:port
    const size_t close = h.find(']');
    return close == std::string_view::npos ? std::string() : std::string(h.substr(1, close - 1));
  }
  const size_t colon = h.find(':');
  return std::string(h.substr(0, colon));
}

bool isLoopbackHostHeader(std::string_view host_header) {
  const std::string name = hostHeaderName(host_header);
  return !name.empty() && (isLocalhostName(name) || isLoopbackLiteral(name));
}

}  // namespace inet::studio

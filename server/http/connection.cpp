#include "http/connection.h"

#include "http/problem.h"

namespace shadelab::http::connections {

std::string refusal(const Error& error) {
  const std::string body = problem(error, "").dump();
  const ErrorCodeInfo& code = info(error.code);
  std::string head = "HTTP/1.1 " + std::to_string(code.status) + " " + std::string(code.title) + "\r\n";
  head += "Content-Type: application/problem+json\r\nConnection: close\r\n";
  if (code.retry_later) head += "Retry-After: 1\r\n";
  return head + "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
}

}  // namespace shadelab::http::connections

// Where a request ends: the connection layer hands handlers only whole requests, and two readers
// of the same bytes must never disagree on that (request smuggling).
#include <gtest/gtest.h>

#include "http/request_framing.h"

namespace shadelab::http {
namespace {

using State = Framed::State;

Framed frame(std::string_view bytes, FramingLimits limits = {}) { return frame_request(bytes, limits); }

TEST(RequestFramingTest, AHeadWithoutBodyEndsAtItsBlankLine) {
  const std::string get = "GET /livez HTTP/1.1\r\nHost: x\r\n\r\n";
  EXPECT_EQ(frame(get.substr(0, get.size() - 1)).state, State::incomplete);
  const auto f = frame(get + "GET /next");  // a pipelined request after it is not part of it
  ASSERT_EQ(f.state, State::complete);
  EXPECT_EQ(f.request_bytes, get.size());
  EXPECT_EQ(frame("GET / HTTP/1.1\nHost: x\n\n").state, State::complete);  // bare LF, as httplib reads it
}

TEST(RequestFramingTest, ContentLengthCountsTheBody) {
  const std::string head = "POST /api/render HTTP/1.1\r\ncontent-length: 5\r\n\r\n";
  EXPECT_EQ(frame(head + "1234").state, State::incomplete);
  const auto f = frame(head + "12345GET");
  ASSERT_EQ(f.state, State::complete);
  EXPECT_EQ(f.head_bytes, head.size());
  EXPECT_EQ(f.request_bytes, head.size() + 5);
}

TEST(RequestFramingTest, ChunkedBodiesEndAtTheLastChunkAndTrailers) {
  const std::string head = "POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n";
  const std::string body = "5;ext=1\r\nhello\r\nA\r\n0123456789\r\n0\r\nX-Trailer: 1\r\n\r\n";
  for (size_t cut = 0; cut < body.size(); ++cut) EXPECT_EQ(frame(head + body.substr(0, cut)).state, State::incomplete) << cut;
  const auto f = frame(head + body + "extra");
  ASSERT_EQ(f.state, State::complete);
  EXPECT_EQ(f.request_bytes, head.size() + body.size());
  EXPECT_EQ(frame(head + "5\r\nhelloXX0\r\n\r\n").state, State::invalid);  // data not followed by CRLF
  EXPECT_EQ(frame(head + "zz\r\n").state, State::invalid);
}

TEST(RequestFramingTest, AmbiguousFramingIsRejected) {
  const auto reject = [](const std::string& headers, ErrorCode code) {
    const auto f = frame("POST / HTTP/1.1\r\n" + headers + "\r\n");
    EXPECT_EQ(f.state, State::invalid) << headers;
    EXPECT_EQ(f.error.code, code) << headers;
  };
  reject("Content-Length: 5\r\nTransfer-Encoding: chunked\r\n", ErrorCode::invalid_argument);
  reject("Content-Length: 5\r\nContent-Length: 6\r\n", ErrorCode::invalid_argument);
  reject("Content-Length: -1\r\n", ErrorCode::invalid_argument);
  reject("Content-Length : 5\r\n", ErrorCode::invalid_argument);
  reject("X: a\r\n folded\r\n", ErrorCode::invalid_argument);
  reject("Transfer-Encoding: gzip, chunked\r\n", ErrorCode::unsupported_transfer_encoding);
  EXPECT_EQ(frame("POST / HTTP/1.1\r\nContent-Length: 5\r\nContent-Length: 5\r\n\r\n12345").state, State::complete);
}

TEST(RequestFramingTest, SizesOverTheLimitsAreRejectedBeforeTheBytesArrive) {
  FramingLimits limits;
  limits.max_head_bytes = 1024;
  limits.max_body_bytes = 100;
  const auto head = frame("GET / HTTP/1.1\r\nX: " + std::string(2000, 'a'), limits);
  EXPECT_EQ(head.state, State::invalid);
  EXPECT_EQ(head.error.code, ErrorCode::headers_too_large);
  const auto body = frame("POST / HTTP/1.1\r\nContent-Length: 101\r\n\r\n", limits);
  EXPECT_EQ(body.error.code, ErrorCode::payload_too_large);
  const auto chunks = frame("POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n40\r\n" + std::string(64, 'a') + "\r\n40\r\n", limits);
  EXPECT_EQ(chunks.error.code, ErrorCode::payload_too_large);
}

TEST(RequestFramingTest, ExpectContinueIsFoundSoItCanBeAnsweredAndDropped) {
  const std::string head = "PUT / HTTP/1.1\r\nExpect: 100-continue\r\nContent-Length: 3\r\n\r\n";
  const auto f = frame(head);
  ASSERT_EQ(f.state, State::incomplete);
  EXPECT_TRUE(f.expects_continue);
  EXPECT_EQ(head.substr(f.expect_begin, f.expect_end - f.expect_begin), "Expect: 100-continue\r\n");
}

}  // namespace
}  // namespace shadelab::http

// The states a handler and its session share (server/job_channel.hpp), transition by
// transition, and the writer's back-pressure across threads.

#include "job_channel.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <thread>

namespace ncpost::server {
namespace {

using namespace std::chrono_literals;
using Answer = JobChannel::Answer;
using Written = JobChannel::Written;
using End = JobChannel::StreamEnd;

StreamHead ok_head() {
  return StreamHead{boost::beast::http::status::ok, 11};
}

TEST(JobChannel, OneAnswerOnly) {
  JobChannel c;
  EXPECT_EQ(c.answer(), Answer::None);
  EXPECT_TRUE(c.claim_response("fanuc-0i"));
  EXPECT_EQ(c.answer(), Answer::Buffered);
  EXPECT_EQ(c.profile(), "fanuc-0i");
  EXPECT_FALSE(c.claim_response("other")) << "a second response is dropped";
  EXPECT_FALSE(c.begin_stream(ok_head(), "other"));
  EXPECT_EQ(c.profile(), "fanuc-0i");
  EXPECT_EQ(c.write("x"), Written::Refused) << "no stream was begun";
}

TEST(JobChannel, StreamPiecesWakeTheSessionOnceUntilTaken) {
  JobChannel c;
  ASSERT_TRUE(c.begin_stream(ok_head(), "linuxcnc"));
  EXPECT_EQ(c.answer(), Answer::Stream);
  ASSERT_TRUE(c.take_head().has_value());
  EXPECT_FALSE(c.take_head().has_value()) << "the head is taken once";
  EXPECT_EQ(c.write("a"), Written::Wake);
  EXPECT_EQ(c.write("b"), Written::Queued) << "one hop is on its way already";
  std::string bytes;
  auto taken = c.take(bytes);
  EXPECT_EQ(bytes, "ab");
  EXPECT_EQ(taken.end, End::Open);
  bytes.clear();
  EXPECT_EQ(c.write("c"), Written::Wake) << "taking cleared the wake-up";
  boost::beast::http::fields trailer;
  trailer.set("Ncpost-Warnings", "0");
  EXPECT_FALSE(c.end_stream(true, trailer)) << "the wake-up for 'c' is still queued";
  taken = c.take(bytes);
  EXPECT_EQ(bytes, "c");
  EXPECT_EQ(taken.end, End::Complete);
  EXPECT_EQ(taken.trailer["Ncpost-Warnings"], "0");
  EXPECT_EQ(c.write("late"), Written::Refused) << "nothing after the end";
  EXPECT_FALSE(c.end_stream(false, {})) << "a stream ends once";
}

TEST(JobChannel, HandlerThatReturnsWithAnOpenStreamCutsIt) {
  JobChannel c;
  ASSERT_TRUE(c.begin_stream(ok_head(), ""));
  EXPECT_EQ(c.handler(), JobChannel::Handler::Running);
  EXPECT_TRUE(c.handler_returned()) << "the session must hear of the cut";
  EXPECT_EQ(c.handler(), JobChannel::Handler::Returned);
  std::string bytes;
  EXPECT_EQ(c.take(bytes).end, End::Cut);
  JobChannel answered;
  EXPECT_TRUE(answered.claim_response(""));
  EXPECT_FALSE(answered.handler_returned()) << "nothing to cut";
}

TEST(JobChannel, TimeLimitBeforeAnyAnswerIsTheSessions504) {
  JobChannel c;
  EXPECT_TRUE(c.time_out());
  EXPECT_TRUE(c.timed_out());
  EXPECT_TRUE(c.cancel_flag().load());
  EXPECT_EQ(c.answer(), Answer::TimedOut);
  EXPECT_FALSE(c.claim_response("")) << "the handler's late answer is dropped";
  EXPECT_FALSE(c.begin_stream(ok_head(), ""));
}

TEST(JobChannel, TimeLimitDuringAStreamLeavesTheCutToTheHandler) {
  JobChannel c;
  ASSERT_TRUE(c.begin_stream(ok_head(), ""));
  EXPECT_FALSE(c.time_out()) << "the head is out: no 504";
  EXPECT_EQ(c.answer(), Answer::Stream);
  EXPECT_TRUE(c.cancel_flag().load());
  EXPECT_EQ(c.write("(ERROR: job time limit)\n"), Written::Wake) << "its error marker goes out";
  EXPECT_FALSE(c.end_stream(false, {})) << "then the cut, with the marker's wake-up";
  std::string bytes;
  EXPECT_EQ(c.take(bytes).end, End::Cut);
}

TEST(JobChannel, ClientGoneRefusesStreamsAndCancels) {
  JobChannel c;
  c.client_gone();
  EXPECT_EQ(c.client(), JobChannel::Client::Gone);
  EXPECT_TRUE(c.cancel_flag().load());
  EXPECT_FALSE(c.begin_stream(ok_head(), ""));
  JobChannel shutdown;
  shutdown.cancel();
  EXPECT_TRUE(shutdown.cancel_flag().load());
  EXPECT_EQ(shutdown.client(), JobChannel::Client::Present) << "a cancelled stream may end";
  ASSERT_TRUE(shutdown.begin_stream(ok_head(), ""));
  EXPECT_NE(shutdown.write("marker"), Written::Refused);
}

TEST(JobChannel, WriterWaitsForTheSocketAndStopsWhenTheClientLeaves) {
  JobChannel c(8);
  ASSERT_TRUE(c.begin_stream(ok_head(), ""));
  EXPECT_EQ(c.write("12345678"), Written::Wake);
  auto blocked = std::async(std::launch::async, [&] { return c.write("9"); });
  EXPECT_EQ(blocked.wait_for(50ms), std::future_status::timeout) << "8 bytes wait: it blocks";
  std::string bytes;
  (void)c.take(bytes);
  EXPECT_EQ(blocked.get(), Written::Wake) << "taking made room";
  EXPECT_EQ(c.write("abcdefg"), Written::Queued);
  auto stopped = std::async(std::launch::async, [&] { return c.write("h"); });
  EXPECT_EQ(stopped.wait_for(50ms), std::future_status::timeout);
  c.client_gone();
  EXPECT_EQ(stopped.get(), Written::Refused);
}

}  // namespace
}  // namespace ncpost::server

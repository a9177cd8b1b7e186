#include "job_channel.hpp"

#include <utility>

namespace ncpost::server {

bool JobChannel::claim_response(std::string_view profile) {
  std::lock_guard lock(mutex_);
  if (answer_ != Answer::None) return false;
  answer_ = Answer::Buffered;
  profile_ = profile;
  return true;
}

bool JobChannel::begin_stream(StreamHead head, std::string_view profile) {
  std::lock_guard lock(mutex_);
  if (answer_ != Answer::None || client_ == Client::Gone) return false;
  answer_ = Answer::Stream;
  head_ = std::move(head);
  profile_ = profile;
  return true;
}

JobChannel::Written JobChannel::write(std::string_view piece) {
  std::unique_lock lock(mutex_);
  const auto stopped = [&] { return client_ == Client::Gone || answer_ == Answer::TimedOut; };
  drained_.wait(lock, [&] { return pending_.size() < max_pending_ || stopped(); });
  if (stopped() || answer_ != Answer::Stream || end_ != StreamEnd::Open) return Written::Refused;
  pending_.append(piece);
  return std::exchange(wakeup_, Wakeup::Queued) == Wakeup::Idle ? Written::Wake : Written::Queued;
}

bool JobChannel::end_stream(bool complete, boost::beast::http::fields trailer) {
  std::lock_guard lock(mutex_);
  if (answer_ != Answer::Stream || end_ != StreamEnd::Open) return false;
  end_ = complete ? StreamEnd::Complete : StreamEnd::Cut;
  trailer_ = std::move(trailer);
  return std::exchange(wakeup_, Wakeup::Queued) == Wakeup::Idle;
}

bool JobChannel::handler_returned() {
  std::lock_guard lock(mutex_);
  handler_ = Handler::Returned;
  if (answer_ != Answer::Stream || end_ != StreamEnd::Open) return false;
  end_ = StreamEnd::Cut;  // it threw between begin_stream() and end_stream()
  return std::exchange(wakeup_, Wakeup::Queued) == Wakeup::Idle;
}

bool JobChannel::time_out() {
  timed_out_.store(true);
  cancel_.store(true);
  std::lock_guard lock(mutex_);
  drained_.notify_all();
  if (answer_ != Answer::None) return false;
  answer_ = Answer::TimedOut;
  return true;
}

void JobChannel::client_gone() {
  cancel_.store(true);
  std::lock_guard lock(mutex_);
  if (handler_ == Handler::Running) client_ = Client::Gone;
  drained_.notify_all();
}

std::optional<StreamHead> JobChannel::take_head() {
  std::lock_guard lock(mutex_);
  return std::exchange(head_, std::nullopt);
}

JobChannel::Taken JobChannel::take(std::string& bytes) {
  std::lock_guard lock(mutex_);
  wakeup_ = Wakeup::Idle;
  bytes.swap(pending_);
  drained_.notify_all();
  Taken taken;
  taken.end = end_;
  if (end_ == StreamEnd::Complete) taken.trailer = std::move(trailer_);
  return taken;
}

void JobChannel::drop_wakeup() {
  std::lock_guard lock(mutex_);
  wakeup_ = Wakeup::Idle;
}

JobChannel::Answer JobChannel::answer() const {
  std::lock_guard lock(mutex_);
  return answer_;
}

JobChannel::Client JobChannel::client() const {
  std::lock_guard lock(mutex_);
  return client_;
}

JobChannel::Handler JobChannel::handler() const {
  std::lock_guard lock(mutex_);
  return handler_;
}

std::string JobChannel::profile() const {
  std::lock_guard lock(mutex_);
  return profile_;
}

}  // namespace ncpost::server

#include "upload.hpp"

#include <algorithm>
#include <boost/asio/post.hpp>

namespace ncpost::server {
StreamedUpload::StreamedUpload(std::size_t size, std::size_t slice_step,
                               boost::asio::thread_pool::executor_type pool,
                               std::shared_ptr<const std::atomic<bool>> cancel,
                               std::shared_ptr<void> slot, const pipeline::Helpers* helpers)
    : slice_step_(std::max<std::size_t>(1, slice_step)),
      pool_(std::move(pool)),
      cancel_(std::move(cancel)),
      slot_(std::move(slot)),
      reader_(pipeline::arriving_text(size, cancel_.get(), helpers)) {}

bool StreamedUpload::append(std::string_view bytes) {
  if (!reader_->append(bytes)) return false;
  hash_.update(bytes);
  std::lock_guard lock(mutex_);
  arrived_ = reader_->appended();
  if (slicing_ || complete_ || gave_up_ || cancelled() || arrived_ - read_to_ < slice_step_)
    return true;
  slicing_ = true;
  boost::asio::post(pool_, [self = shared_from_this()] { self->run_slices(); });
  return true;
}

void StreamedUpload::complete() {
  std::lock_guard lock(mutex_);
  complete_ = true;
}

void StreamedUpload::run_slices() {
  for (;;) {
    std::size_t until = 0;
    {
      std::lock_guard lock(mutex_);
      // Once the body is complete the job reads the rest itself: stop between slices.
      gave_up_ = reader_->gave_up();
      if (complete_ || cancelled() || gave_up_ || arrived_ <= read_to_) {
        slicing_ = false;
        idle_.notify_all();
        return;
      }
      until = std::min(arrived_, read_to_ + kSliceMax);
      read_to_ = until;
    }
    reader_->read_more(until);
  }
}

pipeline::ArrivingText& StreamedUpload::reader() {
  std::unique_lock lock(mutex_);
  complete_ = true;
  idle_.wait(lock, [&] { return !slicing_; });
  read_while_arriving_ = reader_->read_through();
  return *reader_;
}

}  // namespace ncpost::server

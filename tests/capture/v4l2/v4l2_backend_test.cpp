// The V4L2 backend against a simulated sensor behind the V4l2Device seam (frames numbered, the
// exposure in effect lagging the control write by a few frames): brackets, settle frames, error
// frames and retries, pixel formats, open errors and listing.
#include "capture/v4l2/v4l2_backend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include "capture/v4l2/v4l2_controls.h"
#include "capture/v4l2/v4l2_device.h"
#include "support/test_support.h"

namespace glarecam::capture {
namespace {

constexpr std::uint32_t kFourccYuyv = v4l2Fourcc('Y', 'U', 'Y', 'V');

constexpr std::string_view kFakePath = "/dev/video7";

struct FakeConfig {
  int width = 6;
  int height = 4;
  int line_padding_bytes = 0;
  std::vector<std::uint32_t> formats{kFourccYuyv, kV4l2FourccGrey, kV4l2FourccY16};
  bool video_capture = true;
  V4l2ControlRange exposure{1, 10'000, 1, 100};
  std::optional<V4l2ControlRange> analogue_gain = V4l2ControlRange{16, 256, 1, 16};
  std::optional<V4l2ControlRange> digital_gain = V4l2ControlRange{0, 255, 1, 0};
  int lag_frames = 2;       // a write while frame n is in flight shows from frame n + lag
  int frames_per_wait = 1;  // > 1: frames pile up between the backend's waits
  bool deliver = true;      // false: the sensor never delivers a frame
  std::set<std::uint32_t> error_sequences;  // delivered with V4L2_BUF_FLAG_ERROR
  bool frozen_sequence = false;             // a broken driver: every frame carries sequence 0
};

// What the test can observe after the device moved into the camera.
struct FakeState {
  int control_writes = 0;
  bool streaming = false;
  int buffers = 0;
  std::uint32_t frames_produced = 0;
};

// Pixels hold the exposure code in effect (100 µs units), so a frame shows which exposure it had.
class FakeSensor final : public V4l2Device {
 public:
  FakeSensor(FakeConfig config, std::shared_ptr<FakeState> state)
      : config_(std::move(config)), state_(std::move(state)) {
    values_[V4l2Control::kExposureAbsolute] = config_.exposure.default_value;
    writes_.push_back({0, config_.exposure.default_value});
  }

  Result<V4l2Capabilities> queryCapabilities() override {
    return V4l2Capabilities{"fake", "Fake Mono Sensor", "platform:fake", config_.video_capture,
                            true};
  }
  Result<std::vector<std::uint32_t>> enumerateFormats() override { return config_.formats; }
  Result<V4l2FrameSize> largestFrameSize(std::uint32_t) override {
    return V4l2FrameSize{config_.width, config_.height};
  }
  Result<V4l2Format> setFormat(const V4l2Format& requested) override {
    format_ = requested;
    const int bytes = requested.fourcc == kV4l2FourccGrey ? 1 : 2;
    format_.bytes_per_line = requested.width * bytes + config_.line_padding_bytes;
    format_.image_bytes = static_cast<std::size_t>(format_.bytes_per_line) * requested.height;
    return format_;
  }
  Result<std::optional<V4l2ControlRange>> queryControl(V4l2Control control) override {
    switch (control) {
      case V4l2Control::kExposureAbsolute:
        return config_.exposure;
      case V4l2Control::kExposureAuto:
        return V4l2ControlRange{0, 3, 1, 3};
      case V4l2Control::kAutoGain:
        return std::nullopt;
      case V4l2Control::kAnalogueGain:
        return config_.analogue_gain;
      case V4l2Control::kGain:
        return config_.digital_gain;
    }
    return std::nullopt;
  }
  Status setControls(std::span<const V4l2ControlValue> values) override {
    ++state_->control_writes;
    for (const auto& value : values) {
      // Like the kernel's control framework: clamp to the range and round to the step.
      const auto range = queryControl(value.control);
      values_[value.control] = snapToControl(static_cast<double>(value.value), range->value());
    }
    writes_.push_back({next_sequence_, values_[V4l2Control::kExposureAbsolute]});
    return {};
  }
  Result<std::vector<V4l2ControlValue>> getControls(
      std::span<const V4l2Control> controls) override {
    std::vector<V4l2ControlValue> values;
    for (const auto control : controls) values.push_back({control, values_[control]});
    return values;
  }
  Result<int> requestBuffers(int count) override {
    buffers_.assign(static_cast<std::size_t>(count), std::vector<std::byte>(format_.image_bytes));
    queued_.clear();
    ready_.clear();
    state_->buffers = count;
    return count;
  }
  std::span<const std::byte> bufferData(int index) const override {
    return buffers_.at(static_cast<std::size_t>(index));
  }
  Status queueBuffer(int index) override {
    if (index < 0 || index >= static_cast<int>(buffers_.size())) return badInput("bad index");
    queued_.push_back(index);
    return {};
  }
  Result<std::optional<V4l2Buffer>> dequeueBuffer() override {
    if (ready_.empty()) return std::nullopt;
    const auto buffer = ready_.front();
    ready_.erase(ready_.begin());
    return buffer;
  }
  Status streamOn() override {
    state_->streaming = true;
    return {};
  }
  Status streamOff() override {
    state_->streaming = false;
    queued_.clear();
    ready_.clear();
    return {};
  }
  Result<bool> waitForFrame(std::chrono::milliseconds timeout) override {
    if (!state_->streaming) return hardwareError("not streaming");
    if (!ready_.empty()) return true;
    if (!config_.deliver) {
      std::this_thread::sleep_for(timeout);
      return false;
    }
    for (int i = 0; i < config_.frames_per_wait; ++i) produceFrame();
    return !ready_.empty();
  }

 private:
  struct Write {
    std::uint32_t in_flight_sequence;
    std::int64_t exposure_code;
  };

  std::int64_t exposureInEffect(std::uint32_t sequence) const {
    std::int64_t code = writes_.front().exposure_code;
    for (const auto& write : writes_) {
      if (sequence >= write.in_flight_sequence + config_.lag_frames) code = write.exposure_code;
    }
    return code;
  }

  void produceFrame() {
    const auto sequence = next_sequence_++;
    ++state_->frames_produced;
    if (queued_.empty()) return;  // no buffer: the frame is lost, like a real driver
    const int index = queued_.front();
    queued_.erase(queued_.begin());
    fill(buffers_[static_cast<std::size_t>(index)], exposureInEffect(sequence));
    ready_.push_back({index, config_.frozen_sequence ? 0u : sequence, 1'000'000ull * sequence,
                      format_.image_bytes, config_.error_sequences.contains(sequence)});
  }

  void fill(std::vector<std::byte>& data, std::int64_t value) const {
    std::ranges::fill(data, std::byte{0xee});  // padding stays visibly wrong
    for (int y = 0; y < format_.height; ++y) {
      for (int x = 0; x < format_.width; ++x) {
        const auto offset = static_cast<std::size_t>(y) * format_.bytes_per_line;
        if (format_.fourcc == kV4l2FourccGrey) {
          data[offset + x] = static_cast<std::byte>(std::min<std::int64_t>(value, 255));
        } else {
          data[offset + 2 * x] = static_cast<std::byte>(value & 0xff);
          data[offset + 2 * x + 1] = static_cast<std::byte>((value >> 8) & 0xff);
        }
      }
    }
  }

  FakeConfig config_;
  std::shared_ptr<FakeState> state_;
  V4l2Format format_;
  std::map<V4l2Control, std::int64_t> values_;
  std::vector<Write> writes_;
  std::vector<std::vector<std::byte>> buffers_;
  std::vector<int> queued_;
  std::vector<V4l2Buffer> ready_;
  std::uint32_t next_sequence_ = 0;
};

struct FakeRig {
  std::shared_ptr<FakeState> state = std::make_shared<FakeState>();
  std::unique_ptr<CameraBackend> backend;
};

FakeRig fakeRig(FakeConfig config = {}, V4l2Options options = {}) {
  FakeRig rig;
  rig.backend = makeV4l2Backend(
      [config, state = rig.state](const std::string&) -> Result<std::unique_ptr<V4l2Device>> {
        return std::make_unique<FakeSensor>(config, state);
      },
      std::move(options));
  return rig;
}

std::unique_ptr<Camera> openFake(FakeRig& rig, const CameraOptions& options = {}) {
  auto camera = rig.backend->open(kFakePath, options);
  EXPECT_TRUE(camera) << camera.error().message;
  return camera ? std::move(*camera) : nullptr;
}

// Every pixel of the frame holds the exposure code it was exposed with.
void expectExposedWith(const CapturedFrame& frame, double exposure_us) {
  EXPECT_EQ(frame.exposure_us, exposure_us);
  const auto code = static_cast<std::uint16_t>(exposure_us / kExposureAbsoluteUnitUs);
  for (int y = 0; y < frame.image.height(); ++y) {
    for (int x = 0; x < frame.image.width(); ++x) {
      ASSERT_EQ(frame.image.at(x, y), code) << "at " << x << "," << y;
    }
  }
}

const std::vector<ExposureRequest> kBracket{{1000.0, 0.0}, {5000.0, 0.0}, {20'000.0, 0.0}};

TEST(V4l2Backend, BracketFramesCarryTheRequestedExposure) {
  auto rig = fakeRig();
  auto camera = openFake(rig);
  ASSERT_TRUE(camera);
  EXPECT_EQ(camera->info().uri, "v4l2:/dev/video7");
  EXPECT_EQ(camera->info().model, "Fake Mono Sensor");
  EXPECT_EQ(camera->format().pixel_format, "Mono16");  // the deepest offered
  EXPECT_EQ(camera->format().bits_per_pixel, 16);

  auto frames = camera->capture(kBracket);
  ASSERT_TRUE(frames) << frames.error().message;
  ASSERT_EQ(frames->size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    expectExposedWith((*frames)[i], kBracket[i].exposure_us);
    EXPECT_EQ((*frames)[i].gain_db, 0.0);
    EXPECT_EQ((*frames)[i].retries, kDefaultSettleFrames);  // the stale frames dropped
  }
  EXPECT_LT((*frames)[0].timestamp_ns, (*frames)[1].timestamp_ns);
  EXPECT_EQ(rig.state->control_writes, 3);  // one VIDIOC_S_EXT_CTRLS per request
  EXPECT_FALSE(rig.state->streaming);       // stopped and released after the bracket
  EXPECT_EQ(rig.state->buffers, 0);
}

TEST(V4l2Backend, ReportsTheExposureTheCameraApplied) {
  FakeConfig config;
  config.exposure = {1, 10'000, 5, 1};  // codes 1, 6, 11, ...
  auto rig = fakeRig(config);
  auto camera = openFake(rig);
  ASSERT_TRUE(camera);
  const std::vector<ExposureRequest> requests{{1000.0, 6.0}};
  auto frames = camera->capture(requests);
  ASSERT_TRUE(frames) << frames.error().message;
  expectExposedWith(frames->front(), 1100.0);  // code 10 → 11 on the camera's grid
  EXPECT_NEAR(frames->front().gain_db, 20.0 * std::log10(32.0 / 16.0), 1e-12);  // 6 dB → 6.02
}

TEST(V4l2Backend, SettleFramesMustCoverTheSensorsLatency) {
  FakeConfig config;
  config.lag_frames = 5;
  V4l2Options enough;
  enough.settle_frames = 5;
  auto rig = fakeRig(config, enough);
  auto camera = openFake(rig);
  ASSERT_TRUE(camera);
  auto frames = camera->capture(kBracket);
  ASSERT_TRUE(frames) << frames.error().message;
  for (std::size_t i = 0; i < 3; ++i) expectExposedWith((*frames)[i], kBracket[i].exposure_us);
  EXPECT_EQ(frames->back().retries, 5);

  // Too few: the frame kept still has the previous exposure (what the settle rule prevents).
  V4l2Options too_few;
  too_few.settle_frames = 1;
  auto hasty_rig = fakeRig(config, too_few);
  auto hasty = openFake(hasty_rig);
  ASSERT_TRUE(hasty);
  frames = hasty->capture(kBracket);
  ASSERT_TRUE(frames);
  EXPECT_NE((*frames)[1].image.at(0, 0), 50);
}

TEST(V4l2Backend, DrainsFramesThatPiledUpBeforeTheWrite) {
  FakeConfig config;
  config.frames_per_wait = 3;  // two frames wait, exposed before the next request's write
  config.lag_frames = kDefaultSettleFrames;
  auto rig = fakeRig(config);
  auto camera = openFake(rig);
  ASSERT_TRUE(camera);
  auto frames = camera->capture(kBracket);
  ASSERT_TRUE(frames) << frames.error().message;
  for (std::size_t i = 0; i < 3; ++i) expectExposedWith((*frames)[i], kBracket[i].exposure_us);
  EXPECT_GT(frames->back().retries, kDefaultSettleFrames);  // the drained frame counts too
}

TEST(V4l2Backend, DiscardsFramesFlaggedAsErrors) {
  FakeConfig config;
  config.error_sequences = {3, 4};  // the first two settled frames
  auto rig = fakeRig(config);
  auto camera = openFake(rig);
  ASSERT_TRUE(camera);
  auto frames = camera->capture(kBracket);
  ASSERT_TRUE(frames) << frames.error().message;
  expectExposedWith(frames->front(), 1000.0);
  EXPECT_EQ(frames->front().retries, kDefaultSettleFrames + 2);
}

TEST(V4l2Backend, FailsAfterMaxFrameRetries) {
  FakeConfig config;
  for (std::uint32_t s = 0; s < 100; ++s) config.error_sequences.insert(s);
  auto rig = fakeRig(config);
  CameraOptions options;
  options.max_frame_retries = 2;
  auto camera = openFake(rig, options);
  ASSERT_TRUE(camera);
  auto frames = camera->capture(kBracket);
  ASSERT_FALSE(frames);
  EXPECT_EQ(frames.error().code, ErrorCode::kHardware);
  EXPECT_EQ(frames.error().message,
            "v4l2:/dev/video7: frame 1 (exposure 1000 µs): 3 corrupt frames (error flag or "
            "short), more than max_frame_retries = 2");
  EXPECT_FALSE(rig.state->streaming);
  EXPECT_EQ(rig.state->buffers, 0);
}

TEST(V4l2Backend, ADriverWhoseSequenceNeverAdvancesFailsInsteadOfHanging) {
  FakeConfig config;
  config.frozen_sequence = true;
  auto rig = fakeRig(config);
  auto camera = openFake(rig, {});
  ASSERT_TRUE(camera);
  const std::vector<ExposureRequest> two{{1000, 0}, {2000, 0}};
  auto frames = camera->capture(two);
  ASSERT_FALSE(frames);
  EXPECT_NE(frames.error().message.find("without the new exposure taking effect"),
            std::string::npos)
      << frames.error().message;
  EXPECT_FALSE(rig.state->streaming);
}

TEST(V4l2Backend, ASensorThatNeverDeliversTimesOut) {
  FakeConfig config;
  config.deliver = false;
  auto rig = fakeRig(config);
  CameraOptions options;
  options.frame_timeout_s = 0.05;
  auto camera = openFake(rig, options);
  ASSERT_TRUE(camera);
  const auto start = std::chrono::steady_clock::now();
  auto frames = camera->capture(kBracket);
  const auto elapsed = std::chrono::steady_clock::now() - start;
  ASSERT_FALSE(frames);
  EXPECT_EQ(frames.error().code, ErrorCode::kHardware);
  EXPECT_EQ(frames.error().message,
            "v4l2:/dev/video7: frame 1 (exposure 1000 µs): no frame within 0.051 s (frame "
            "timeout 0.05 s + exposure)");
  EXPECT_LT(elapsed, std::chrono::seconds(2));  // 51 ms expected; generous for a loaded CI
  EXPECT_FALSE(rig.state->streaming);
}

TEST(V4l2Backend, ReadsY10AndGreyWithLinePadding) {
  FakeConfig config;
  config.formats = {kV4l2FourccY10, kV4l2FourccGrey};
  config.line_padding_bytes = 6;
  auto rig = fakeRig(config);
  auto camera = openFake(rig);
  ASSERT_TRUE(camera);
  EXPECT_EQ(camera->format().pixel_format, "Mono10");
  const std::vector<ExposureRequest> requests{{30'000.0, 0.0}};  // code 300: needs 9 bits
  auto frames = camera->capture(requests);
  ASSERT_TRUE(frames) << frames.error().message;
  expectExposedWith(frames->front(), 30'000.0);

  CameraOptions grey;
  grey.pixel_format = "Mono8";
  auto grey_camera = openFake(rig, grey);
  ASSERT_TRUE(grey_camera);
  EXPECT_EQ(grey_camera->format().pixel_format, "Mono8");
  EXPECT_EQ(grey_camera->format().bits_per_pixel, 8);
  const std::vector<ExposureRequest> short_exposure{{2000.0, 0.0}};
  frames = grey_camera->capture(short_exposure);
  ASSERT_TRUE(frames) << frames.error().message;
  expectExposedWith(frames->front(), 2000.0);
}

TEST(V4l2Backend, OpenErrorsNameTheUri) {
  FakeConfig yuyv_only;
  yuyv_only.formats = {kFourccYuyv};
  auto rig = fakeRig(yuyv_only);
  auto camera = rig.backend->open(kFakePath, {});
  ASSERT_FALSE(camera);
  EXPECT_EQ(camera.error().code, ErrorCode::kHardware);
  EXPECT_EQ(camera.error().message,
            "v4l2:/dev/video7: no supported mono format (GREY, Y10, Y12, Y16); the device "
            "offers: YUYV");

  FakeConfig metadata_node;
  metadata_node.video_capture = false;
  rig = fakeRig(metadata_node);
  camera = rig.backend->open(kFakePath, {});
  ASSERT_FALSE(camera);
  EXPECT_EQ(camera.error().message,
            "v4l2:/dev/video7: not a video capture device ('Fake Mono Sensor', driver fake: a "
            "metadata or output node?)");

  rig = fakeRig();
  CameraOptions mono12;
  mono12.pixel_format = "Mono12";
  camera = rig.backend->open(kFakePath, mono12);
  ASSERT_FALSE(camera);
  EXPECT_EQ(camera.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(camera.error().message,
            "v4l2:/dev/video7: pixel format Mono12 (Y12) not offered; the device offers: YUYV, "
            "GREY, Y16");
}

TEST(V4l2Backend, ListsCaptureNodesInNumericOrder) {
  testing::TempDir dev;
  for (const char* name : {"video10", "video2", "video0", "vbi0", "videoX", "media0"}) {
    std::ofstream(dev / name) << "";
  }
  V4l2Options options;
  options.device_directory = dev.path().string();
  auto state = std::make_shared<FakeState>();
  auto backend = makeV4l2Backend(
      [state](const std::string& path) -> Result<std::unique_ptr<V4l2Device>> {
        FakeConfig config;
        config.video_capture = !path.ends_with("video2");  // a metadata node
        return std::make_unique<FakeSensor>(config, state);
      },
      options);
  auto cameras = backend->list();
  ASSERT_TRUE(cameras) << cameras.error().message;
  ASSERT_EQ(cameras->size(), 2u);
  EXPECT_EQ((*cameras)[0].uri, "v4l2:" + (dev / "video0").string());
  EXPECT_EQ((*cameras)[1].uri, "v4l2:" + (dev / "video10").string());
  EXPECT_EQ((*cameras)[0].backend, "v4l2");
  EXPECT_EQ((*cameras)[0].detail, "platform:fake (driver fake)");

  auto first = backend->open("", {});  // empty id: the first camera listed
  ASSERT_TRUE(first) << first.error().message;
  EXPECT_EQ((*first)->info().uri, (*cameras)[0].uri);
}

}  // namespace
}  // namespace glarecam::capture

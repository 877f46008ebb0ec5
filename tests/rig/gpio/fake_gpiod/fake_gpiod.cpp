#include "fake_gpiod.h"

#include <gpiod.h>

#include <cerrno>
#include <memory>

struct gpiod_line {
  gpiod_chip* chip = nullptr;
  unsigned offset = 0;
};

struct gpiod_chip {
  fake_gpiod::Chip* chip = nullptr;
  std::map<unsigned, std::unique_ptr<gpiod_line>> lines;  // one object per offset, as libgpiod
};

namespace fake_gpiod {

Kernel& kernel() {
  static Kernel instance;
  return instance;
}

void reset() { kernel() = Kernel{}; }

Chip& addChip(const std::string& path, const std::string& name, const std::string& label,
              unsigned count) {
  Chip chip{name, label, {}};
  for (unsigned offset = 0; offset < count; ++offset) {
    Line line;
    line.name = "GPIO" + std::to_string(offset);
    chip.lines.push_back(std::move(line));
  }
  return kernel().chips[path] = std::move(chip);
}

}  // namespace fake_gpiod

namespace {

fake_gpiod::Line& state(gpiod_line* line) { return line->chip->chip->lines.at(line->offset); }

gpiod_chip* openChip(fake_gpiod::Chip* chip) {
  if (fake_gpiod::kernel().open_errno != 0) {
    errno = fake_gpiod::kernel().open_errno;
    return nullptr;
  }
  if (!chip) {
    errno = ENOENT;
    return nullptr;
  }
  ++fake_gpiod::kernel().open_handles;
  auto* handle = new gpiod_chip;
  handle->chip = chip;
  return handle;
}

fake_gpiod::Chip* chipWhere(bool (*match)(const fake_gpiod::Chip&, const char*), const char* key) {
  for (auto& [path, chip] : fake_gpiod::kernel().chips) {
    if (match(chip, key)) return &chip;
  }
  return nullptr;
}

}  // namespace

gpiod_chip* gpiod_chip_open(const char* path) {
  const auto found = fake_gpiod::kernel().chips.find(path);
  return openChip(found == fake_gpiod::kernel().chips.end() ? nullptr : &found->second);
}

gpiod_chip* gpiod_chip_open_by_name(const char* name) {
  return openChip(
      chipWhere([](const fake_gpiod::Chip& c, const char* k) { return c.name == k; }, name));
}

gpiod_chip* gpiod_chip_open_by_number(unsigned int number) {
  return gpiod_chip_open_by_name(("gpiochip" + std::to_string(number)).c_str());
}

gpiod_chip* gpiod_chip_open_by_label(const char* label) {
  return openChip(
      chipWhere([](const fake_gpiod::Chip& c, const char* k) { return c.label == k; }, label));
}

void gpiod_chip_close(gpiod_chip* chip) {
  // As libgpiod: closing releases the lines still requested (logged, so tests see it happen).
  for (auto& [offset, line] : chip->lines) {
    if (state(line.get()).requested) {
      fake_gpiod::kernel().log.push_back("close releases " + std::to_string(offset));
      state(line.get()).requested = false;
    }
  }
  fake_gpiod::kernel().log.push_back("close " + chip->chip->name);
  --fake_gpiod::kernel().open_handles;
  delete chip;
}

const char* gpiod_chip_name(gpiod_chip* chip) { return chip->chip->name.c_str(); }
const char* gpiod_chip_label(gpiod_chip* chip) { return chip->chip->label.c_str(); }
unsigned int gpiod_chip_num_lines(gpiod_chip* chip) {
  return static_cast<unsigned>(chip->chip->lines.size());
}

gpiod_line* gpiod_chip_get_line(gpiod_chip* chip, unsigned int offset) {
  if (offset >= chip->chip->lines.size()) {
    errno = EINVAL;
    return nullptr;
  }
  std::unique_ptr<gpiod_line>& line = chip->lines[offset];
  if (!line) line.reset(new gpiod_line{chip, offset});
  return line.get();
}

gpiod_line* gpiod_chip_find_line(gpiod_chip* chip, const char* name) {
  for (unsigned offset = 0; offset < chip->chip->lines.size(); ++offset) {
    if (chip->chip->lines[offset].name == name) return gpiod_chip_get_line(chip, offset);
  }
  errno = ENOENT;
  return nullptr;
}

unsigned int gpiod_line_offset(gpiod_line* line) { return line->offset; }

int gpiod_line_update(gpiod_line*) { return 0; }

const char* gpiod_line_consumer(gpiod_line* line) {
  const fake_gpiod::Line& s = state(line);
  if (!s.other_consumer.empty()) return s.other_consumer.c_str();
  return s.requested ? s.consumer.c_str() : nullptr;
}

int gpiod_line_request(gpiod_line* line, const gpiod_line_request_config* config, int default_val) {
  fake_gpiod::Line& s = state(line);
  if (s.requested || !s.other_consumer.empty()) {
    errno = EBUSY;
    return -1;
  }
  if (s.request_errno != 0) {
    errno = s.request_errno;
    return -1;
  }
  s.requested = true;
  s.consumer = config->consumer;
  s.request_type = config->request_type;
  s.flags = config->flags;
  if (config->request_type == GPIOD_LINE_REQUEST_DIRECTION_OUTPUT) s.value = default_val;
  fake_gpiod::kernel().log.push_back("request " + std::to_string(line->offset) + " " + s.consumer);
  return 0;
}

void gpiod_line_release(gpiod_line* line) {
  fake_gpiod::Line& s = state(line);
  if (!s.requested) {
    fake_gpiod::kernel().log.push_back("release of an unrequested line " +
                                       std::to_string(line->offset));
    return;
  }
  s.requested = false;
  fake_gpiod::kernel().log.push_back("release " + std::to_string(line->offset));
}

int gpiod_line_get_value(gpiod_line* line) {
  const fake_gpiod::Line& s = state(line);
  if (s.io_errno != 0) {
    errno = s.io_errno;
    return -1;
  }
  return s.value;
}

int gpiod_line_set_value(gpiod_line* line, int value) {
  fake_gpiod::Line& s = state(line);
  if (s.io_errno != 0) {
    errno = s.io_errno;
    return -1;
  }
  s.value = value;
  fake_gpiod::kernel().log.push_back("set " + std::to_string(line->offset) + " " +
                                     std::to_string(value));
  return 0;
}

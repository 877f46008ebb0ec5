#include "rig/illuminance/modbus_instrument.h"

#include <fmt/format.h>
#include <modbus/modbus.h>

#include <cerrno>
#include <vector>

namespace glarecam::rig {

namespace {

// A libmodbus context: closed and freed once.
class ModbusHandle {
 public:
  explicit ModbusHandle(modbus_t* ctx) : ctx_(ctx) {}
  ~ModbusHandle() {
    if (!ctx_) return;
    modbus_close(ctx_);
    modbus_free(ctx_);
  }
  ModbusHandle(const ModbusHandle&) = delete;
  ModbusHandle& operator=(const ModbusHandle&) = delete;
  modbus_t* get() const { return ctx_; }

 private:
  modbus_t* ctx_;
};

std::string modbusFailure(const IlluminanceConfig& config, int error) {
  if (error == ETIMEDOUT)
    return fmt::format("{}: no reply within {} ms (timeout: is slave_id {} right, the line wired?)",
                       config.where(), config.timeout.count(), config.slave_id);
  if (error == ECONNREFUSED)
    return fmt::format("{}: connection refused (no instrument listening)", config.where());
  if (error > MODBUS_ENOBASE && error <= MODBUS_ENOBASE + MODBUS_EXCEPTION_GATEWAY_TARGET)
    return fmt::format("{}: exception reply: {}", config.where(), modbus_strerror(error));
  return fmt::format("{}: {}", config.where(), modbus_strerror(error));
}

bool isExceptionReply(int error) {
  return error > MODBUS_ENOBASE && error <= MODBUS_ENOBASE + MODBUS_EXCEPTION_GATEWAY_TARGET;
}

class ModbusInstrument final : public IlluminanceInstrument {
 public:
  ModbusInstrument(IlluminanceConfig config, modbus_t* ctx)
      : config_(std::move(config)), ctx_(ctx) {
    info_.description = config_.description();
    info_.instrument_u_rel = config_.uncertainty_pct / 100;
    info_.efficacy_u_rel = config_.units == IlluminanceUnits::kLux
                               ? 0.0
                               : config_.efficacy_u_lm_w / config_.efficacy_lm_w;
  }

  const IlluminanceInstrumentInfo& info() const override { return info_; }

  Status connect() {
    if (connected_) return {};
    if (modbus_connect(ctx_.get()) != 0) {
      const int error = errno;
      if (config_.transport == ModbusTransport::kRtu)
        return hardwareError(fmt::format("{}: cannot open {}: {}", config_.where(), config_.device,
                                         modbus_strerror(error)));
      return hardwareError(modbusFailure(config_, error));
    }
    connected_ = true;
    return {};
  }

  Result<IlluminanceReading> read() override {
    GLARECAM_CHECK(connect());
    std::vector<std::uint16_t> registers(static_cast<std::size_t>(config_.registerCount()));
    IlluminanceReading reading;
    reading.requested_at = std::chrono::steady_clock::now();
    const int count = config_.registerCount();
    const int got =
        config_.register_type == RegisterType::kInput
            ? modbus_read_input_registers(ctx_.get(), config_.address, count, registers.data())
            : modbus_read_registers(ctx_.get(), config_.address, count, registers.data());
    if (got != count) {
      const int error = got < 0 ? errno : EMBBADDATA;
      if (!isExceptionReply(error)) {  // the link is in doubt: open it again next time
        modbus_close(ctx_.get());
        connected_ = false;
      }
      return hardwareError(modbusFailure(config_, error));
    }
    reading.raw_value = decodeRegisters(config_, registers);
    GLARECAM_ASSIGN(reading.illuminance_lx, illuminanceLx(config_, reading.raw_value));
    return reading;
  }

 private:
  IlluminanceConfig config_;
  ModbusHandle ctx_;
  IlluminanceInstrumentInfo info_;
  bool connected_ = false;
};

}  // namespace

Result<std::unique_ptr<IlluminanceInstrument>> openModbusInstrument(
    const IlluminanceConfig& config) {
  GLARECAM_CHECK(config.validate());
  modbus_t* ctx = config.transport == ModbusTransport::kRtu
                      ? modbus_new_rtu(config.device.c_str(), config.baud, config.parity,
                                       config.data_bits, config.stop_bits)
                      : modbus_new_tcp(config.host.c_str(), config.port);
  if (!ctx) return hardwareError(fmt::format("{}: {}", config.where(), modbus_strerror(errno)));
  auto instrument = std::make_unique<ModbusInstrument>(config, ctx);
  const auto timeout_us = std::chrono::microseconds(config.timeout).count();
  if (modbus_set_slave(ctx, config.slave_id) != 0 ||
      modbus_set_response_timeout(ctx, static_cast<std::uint32_t>(timeout_us / 1'000'000),
                                  static_cast<std::uint32_t>(timeout_us % 1'000'000)) != 0)
    return hardwareError(fmt::format("{}: {}", config.where(), modbus_strerror(errno)));
  return std::unique_ptr<IlluminanceInstrument>(std::move(instrument));
}

}  // namespace glarecam::rig

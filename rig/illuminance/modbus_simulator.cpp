#include "rig/illuminance/modbus_simulator.h"

#include <fmt/format.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <thread>
#include <vector>

namespace glarecam::rig {

namespace {

// How often the server looks at its stop flag and fault between requests.
constexpr int kSimulatorPollMs = 20;
constexpr double kOutOfRangeIrradianceWM2 = 2000.0;  // 186 klx at 93 lm/W
constexpr double kOutOfRangeIlluminanceLx = 200'000.0;
constexpr double kNegativeIrradianceWM2 = -5.0;
constexpr double kNegativeIlluminanceLx = -500.0;

// The served map for an irradiance and an illuminance (modbus_simulator.h).
void fillSimulatorRegisters(double irradiance_w_m2, double illuminance_lx,
                            std::span<std::uint16_t, kSimulatorRegisterCount> map) {
  encodeRegisters(RegisterDataType::kFloat32, WordOrder::kBig, irradiance_w_m2, map.subspan(0, 2));
  encodeRegisters(RegisterDataType::kFloat32, WordOrder::kLittle, irradiance_w_m2,
                  map.subspan(2, 2));
  encodeRegisters(RegisterDataType::kUint16, WordOrder::kBig, irradiance_w_m2 * 10,
                  map.subspan(4, 1));
  encodeRegisters(RegisterDataType::kInt16, WordOrder::kBig, irradiance_w_m2 * 10,
                  map.subspan(5, 1));
  encodeRegisters(RegisterDataType::kUint32, WordOrder::kBig, irradiance_w_m2 * 1000,
                  map.subspan(6, 2));
  encodeRegisters(RegisterDataType::kFloat32, WordOrder::kBig, illuminance_lx, map.subspan(8, 2));
  encodeRegisters(RegisterDataType::kUint16, WordOrder::kBig, illuminance_lx / 10,
                  map.subspan(10, 1));
}

}  // namespace

class ModbusInstrumentSimulator::Server {
 public:
  explicit Server(ModbusSimulatorOptions options)
      : options_(options),
        illuminance_lx_(options.illuminance_lx),
        fault_(static_cast<int>(options.fault)) {}

  ~Server() {
    if (thread_.joinable()) {
      thread_.request_stop();
      thread_.join();
    }
    closeAll();
    if (mapping_) modbus_mapping_free(mapping_);
    if (ctx_) modbus_free(ctx_);
  }

  Status listenOnFreePort() {
    modbus_t* probe = modbus_new_tcp("127.0.0.1", 0);
    if (!probe) return ioError("simulated instrument: " + std::string(modbus_strerror(errno)));
    listener_ = modbus_tcp_listen(probe, 4);
    const int listen_errno = errno;
    modbus_free(probe);
    if (listener_ < 0)
      return ioError("simulated instrument: cannot listen on 127.0.0.1: " +
                     std::string(modbus_strerror(listen_errno)));
    sockaddr_in address{};
    socklen_t length = sizeof(address);
    if (getsockname(listener_, reinterpret_cast<sockaddr*>(&address), &length) != 0)
      return ioError("simulated instrument: getsockname: " + errnoText(errno));
    port_ = ntohs(address.sin_port);
    ctx_ = modbus_new_tcp("127.0.0.1", port_);
    mapping_ = modbus_mapping_new(0, 0, kSimulatorRegisterCount, kSimulatorRegisterCount);
    if (!ctx_ || !mapping_) return ioError("simulated instrument: out of memory");
    if (fault() == SimulatedInstrumentFault::kDead) closeAll();  // refused from the start
    thread_ = std::jthread([this](std::stop_token stop) { serve(stop); });
    return {};
  }

  int port() const { return port_; }
  void setIlluminanceLx(double lx) { illuminance_lx_.store(lx); }
  void setFault(SimulatedInstrumentFault fault) { fault_.store(static_cast<int>(fault)); }
  int answered() const { return answered_.load(); }

 private:
  SimulatedInstrumentFault fault() const {
    return static_cast<SimulatedInstrumentFault>(fault_.load());
  }

  void closeAll() {
    for (const int client : clients_) close(client);
    clients_.clear();
    if (listener_ >= 0) close(listener_);
    listener_ = -1;
  }

  void serve(std::stop_token stop) {
    while (!stop.stop_requested()) {
      if (fault() == SimulatedInstrumentFault::kDead) {
        closeAll();  // the port refuses connections
      } else if (listener_ < 0) {
        listener_ = modbus_tcp_listen(ctx_, 4);  // back from the dead, on the same port
      }
      std::vector<pollfd> fds;
      if (listener_ >= 0) fds.push_back({listener_, POLLIN, 0});
      for (const int client : clients_) fds.push_back({client, POLLIN, 0});
      if (fds.empty()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(kSimulatorPollMs));
        continue;
      }
      if (poll(fds.data(), fds.size(), kSimulatorPollMs) <= 0) continue;
      for (const pollfd& fd : fds) {
        if (!(fd.revents & (POLLIN | POLLHUP | POLLERR))) continue;
        if (fd.fd == listener_) {
          const int client = accept(listener_, nullptr, nullptr);
          if (client >= 0) clients_.push_back(client);
        } else if (!answer(fd.fd)) {
          close(fd.fd);
          std::erase(clients_, fd.fd);
        }
      }
    }
  }

  // One request from `client`; false when the client has gone.
  bool answer(int client) {
    std::array<std::uint8_t, MODBUS_TCP_MAX_ADU_LENGTH> query{};
    modbus_set_socket(ctx_, client);
    const int length = modbus_receive(ctx_, query.data());
    modbus_set_socket(ctx_, -1);
    if (length < 0) return false;
    if (length == 0) return true;
    const int unit = query[modbus_get_header_length(ctx_) - 1];
    const SimulatedInstrumentFault now = fault();
    if (unit != options_.slave_id || now == SimulatedInstrumentFault::kTimeout) return true;
    ++answered_;  // before the reply: a client that has it sees the count
    modbus_set_socket(ctx_, client);
    if (now == SimulatedInstrumentFault::kException) {
      modbus_reply_exception(ctx_, query.data(), MODBUS_EXCEPTION_SLAVE_OR_SERVER_FAILURE);
    } else {
      double lx = illuminance_lx_.load();
      double w_m2 = lx / options_.efficacy_lm_w;
      if (now == SimulatedInstrumentFault::kOutOfRange) {
        w_m2 = kOutOfRangeIrradianceWM2;
        lx = kOutOfRangeIlluminanceLx;
      } else if (now == SimulatedInstrumentFault::kNegative) {
        w_m2 = kNegativeIrradianceWM2;
        lx = kNegativeIlluminanceLx;
      }
      std::array<std::uint16_t, kSimulatorRegisterCount> map{};
      fillSimulatorRegisters(w_m2, lx, map);
      std::copy(map.begin(), map.end(), mapping_->tab_input_registers);
      std::copy(map.begin(), map.end(), mapping_->tab_registers);
      modbus_reply(ctx_, query.data(), length, mapping_);
    }
    modbus_set_socket(ctx_, -1);
    return true;
  }

  ModbusSimulatorOptions options_;
  std::atomic<double> illuminance_lx_;
  std::atomic<int> fault_;
  std::atomic<int> answered_{0};
  modbus_t* ctx_ = nullptr;
  modbus_mapping_t* mapping_ = nullptr;
  int listener_ = -1;
  int port_ = 0;
  std::vector<int> clients_;
  std::jthread thread_;  // last: stopped before the members it uses go
};

Result<std::unique_ptr<ModbusInstrumentSimulator>> ModbusInstrumentSimulator::start(
    ModbusSimulatorOptions options) {
  auto server = std::make_unique<Server>(options);
  GLARECAM_CHECK(server->listenOnFreePort());
  return std::unique_ptr<ModbusInstrumentSimulator>(
      new ModbusInstrumentSimulator(std::move(server)));
}

ModbusInstrumentSimulator::ModbusInstrumentSimulator(std::unique_ptr<Server> server)
    : server_(std::move(server)) {}
ModbusInstrumentSimulator::~ModbusInstrumentSimulator() = default;

int ModbusInstrumentSimulator::port() const { return server_->port(); }
void ModbusInstrumentSimulator::setIlluminanceLx(double lx) { server_->setIlluminanceLx(lx); }
void ModbusInstrumentSimulator::setFault(SimulatedInstrumentFault fault) {
  server_->setFault(fault);
}
int ModbusInstrumentSimulator::requestsAnswered() const { return server_->answered(); }

}  // namespace glarecam::rig

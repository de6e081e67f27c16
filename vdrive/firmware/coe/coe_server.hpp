#pragma once
// CoE in the mailbox (ETG.1000.6): routes each CoE request by its service to the SDO server or
// to SDO Information (when the product's SII CoE details advertise it, bit1); any other service a
// master may send is answered with mailbox error 0x04 "service not supported". Owns the
// parameter store (1010h/1011h) of this drive.
#include <memory>
#include <string>

#include "vdrive/firmware/firmware_module.hpp"
#include "vdrive/firmware/mailbox/protocol.hpp"

namespace vdrive::firmware::coe {

class ParameterStore;
class SdoServer;
class SdoInfo;

class CoeServer final : public mailbox::Protocol {
public:
  CoeServer(FirmwareContext& context, const std::string& state_dir);
  ~CoeServer() override;

  mailbox::Outcome on_request(std::span<const std::uint8_t> request, std::span<std::uint8_t> reply,
                              Nanos now) override;
  std::size_t next_reply(std::span<std::uint8_t> reply) override;
  void reset() override;

  ParameterStore& parameters() { return *parameters_; }

private:
  bool sdo_info_;
  std::unique_ptr<ParameterStore> parameters_;
  std::unique_ptr<SdoServer> sdo_;
  std::unique_ptr<SdoInfo> info_;
};

}  // namespace vdrive::firmware::coe

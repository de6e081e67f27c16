#include "vdrive/firmware/coe/coe_server.hpp"

#include "ethercat/coe.hpp"
#include "ethercat/little_endian.hpp"
#include "vdrive/firmware/coe/parameter_store.hpp"
#include "vdrive/firmware/coe/sdo_info.hpp"
#include "vdrive/firmware/coe/sdo_server.hpp"
#include "vdrive/od/object_store.hpp"
#include "vdrive/profile/product_profile.hpp"

namespace vdrive::firmware::coe {

using ecat::coe::kCoeHeaderSize;
using ecat::coe::Service;
using ecat::coe::service_of;

namespace {
constexpr std::uint8_t kCoeSdoInfo = 0x02;  // SII General CoE details bit1
}  // namespace

CoeServer::CoeServer(FirmwareContext& context, const std::string& state_dir)
    : sdo_info_((context.profile.coe_details & kCoeSdoInfo) != 0),
      parameters_(std::make_unique<ParameterStore>(context.profile, context.objects, state_dir)),
      sdo_(std::make_unique<SdoServer>(context.profile, context.objects, context.esm,
                                       parameters_.get(), context.sdo_aborts)),
      info_(std::make_unique<SdoInfo>(context.objects.dictionary(),
                                      context.objects.dictionary().find(kStoreParameters) !=
                                          nullptr)) {}

CoeServer::~CoeServer() = default;

mailbox::Outcome CoeServer::on_request(std::span<const std::uint8_t> request,
                                       std::span<std::uint8_t> reply, Nanos /*now*/) {
  if (request.size() < kCoeHeaderSize) {
    return mailbox::Outcome::mailbox_error(ecat::mailbox::ErrorCode::SizeTooShort);
  }
  switch (service_of(request)) {
    case Service::SdoRequest:
      info_->reset();
      return sdo_->on_request(request, reply);
    case Service::SdoInformation:
      if (!sdo_info_) break;
      return info_->on_request(request, reply);
    default:
      break;
  }
  return mailbox::Outcome::mailbox_error(ecat::mailbox::ErrorCode::ServiceNotSupported);
}

std::size_t CoeServer::next_reply(std::span<std::uint8_t> reply) {
  return info_->next_fragment(reply);
}

void CoeServer::reset() {
  sdo_->reset();
  info_->reset();
}

}  // namespace vdrive::firmware::coe

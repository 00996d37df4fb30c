#include "isobus/tc_partner.hpp"

#include <utility>

#include "isobus/address_claim.hpp"
#include "isobus/iso_name.hpp"

namespace spread::isobus {

bool is_task_controller_name(std::uint64_t name) {
  const IsoName n = decode_name(name);
  return n.industry_group == kIndustryGroupAgriculture && n.device_class == kDeviceClassNonSpecific &&
         n.function == kFunctionTaskController;
}

void TaskControllerPartner::lose(std::string why) {
  partner_.reset();
  last_loss_ = std::move(why);
  ++counters_.partners_lost;
}

bool TaskControllerPartner::on_address_claimed(std::uint8_t source, std::uint64_t name) {
  if (source < kNullAddress) names_[source] = name;
  if (!partner_) return false;
  // ISO 11783-5: an address belongs to the NAME that last claimed it. Another NAME at the partner's
  // address has taken it (the partner lost the contention, or was replaced); the partner's NAME at another
  // address, or saying it cannot claim, has left the address we know it by.
  if (source == partner_->address && name != partner_->name) {
    lose("its address was claimed by another NAME");
    return true;
  }
  if (name == partner_->name && source != partner_->address) {
    lose(source == kNullAddress ? "it cannot claim an address" : "it claimed another address");
    return true;
  }
  return false;
}

TaskControllerPartner::Status TaskControllerPartner::on_tc_status(std::uint8_t source, Nanoseconds now) {
  if (is_partner(source)) {
    partner_->last_status = now;
    return Status::kPartner;
  }
  const bool claimed_as_tc = source < kNullAddress && names_[source] && is_task_controller_name(*names_[source]);
  if (!claimed_as_tc) {
    ++counters_.status_not_from_a_tc;
    return Status::kNotATc;
  }
  if (partner_) {
    ++counters_.status_from_other_tc;
    return Status::kOtherTc;
  }
  partner_ = Partner{source, *names_[source], now};
  ++counters_.partners_chosen;
  return Status::kPartner;
}

bool TaskControllerPartner::update(Nanoseconds now, Nanoseconds timeout) {
  if (!partner_ || now - partner_->last_status <= timeout) return false;
  lose("its TC status stopped");
  return true;
}

}  // namespace spread::isobus

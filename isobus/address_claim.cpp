#include "isobus/address_claim.hpp"

#include <algorithm>

namespace spread::isobus {

AddressClaim::AddressClaim(std::uint64_t name, std::uint8_t preferred_address)
    : name_(name), preferred_(preferred_address) {}

void AddressClaim::queue(ClaimMessage message, Nanoseconds due) { pending_.push_back({message, due}); }

Nanoseconds AddressClaim::cannot_claim_delay() const {
  // Pseudo-random but reproducible: two functions with different NAMEs (identity numbers differ between
  // units) usually draw different delays, and a test sees the same delay every run.
  std::uint64_t x = name_ * 0x9E3779B97F4A7C15ull;
  x ^= x >> 29;
  return kCannotClaimDelayUnit * static_cast<std::int64_t>(x & 0xFFu);
}

void AddressClaim::claim(std::uint8_t address, Nanoseconds now) {
  address_ = address;
  state_ = ClaimState::kClaiming;
  claim_sent_at_ = now;
  queue({address_, name_}, now);
}

void AddressClaim::start(Nanoseconds now) {
  if (state_ != ClaimState::kNotStarted) return;
  if (preferred_ < kNullAddress) {
    claim(preferred_, now);
    return;
  }
  lose(now);  // no usable preferred address: try the self-configurable range, else cannot claim
}

std::optional<std::uint8_t> AddressClaim::next_candidate() const {
  if (!self_configurable()) return std::nullopt;
  // First an address nobody has claimed, then one whose holder has a higher NAME (we would win it).
  // The search starts after the current address so that two losers do not chase the same address.
  const int span = kSelfConfigurableLast - kSelfConfigurableFirst + 1;
  const int start = (address_ >= kSelfConfigurableFirst && address_ <= kSelfConfigurableLast)
                        ? address_ - kSelfConfigurableFirst + 1
                        : 0;
  for (const bool allow_weaker_holder : {false, true}) {
    for (int i = 0; i < span; ++i) {
      const auto candidate = static_cast<std::uint8_t>(kSelfConfigurableFirst + (start + i) % span);
      if (candidate == address_) continue;
      const auto& holder = holders_[candidate];
      if (!holder) return candidate;
      if (allow_weaker_holder && *holder > name_) return candidate;
    }
  }
  return std::nullopt;
}

void AddressClaim::lose(Nanoseconds now) {
  if (const auto next = next_candidate()) {
    claim(*next, now);
    return;
  }
  // §4.4.4.3: a function that cannot claim an address says so from the null address and stays silent.
  state_ = ClaimState::kCannotClaim;
  address_ = kNullAddress;
  queue({kNullAddress, name_}, now + cannot_claim_delay());
}

void AddressClaim::on_address_claimed(std::uint8_t source, std::uint64_t name, Nanoseconds now) {
  const bool active = state_ == ClaimState::kClaiming || state_ == ClaimState::kClaimed;
  if (name == name_) {
    if (state_ != ClaimState::kNotStarted) on_own_name(now);
    return;
  }
  if (source >= kNullAddress) return;  // another function's cannot-claim: it holds nothing
  holders_[source] = name;
  if (!active) return;
  if (source != address_) return;
  if (name_ < name) {
    // §4.4.3.3: the lower NAME wins; the winner repeats its claim so the loser and every other node see it.
    ++counters_.contentions_won;
    queue({address_, name_}, now);
    return;
  }
  ++counters_.contentions_lost;
  lose(now);
}

Nanoseconds AddressClaim::hold_off() const {
  return kDuplicateNameHoldOff * (1 << std::min(std::max(hold_offs_ - 1, 0), kDuplicateNameMaxDoublings));
}

void AddressClaim::on_own_name(Nanoseconds now) {
  // ISO 11783-5 §4.3: a NAME identifies one control function on the network. Our own frames never come
  // back (CAN_RAW without RECV_OWN_MSGS, spread-canbus without echo), so our NAME from another node is
  // either a stray or spoofed frame, or a second unit with our identity number.
  ++counters_.duplicate_names;
  const bool repeated = last_own_name_ && now - *last_own_name_ <= kDuplicateNameWindow;
  last_own_name_ = now;
  if (reclaim_at_) {
    reclaim_at_ = now + hold_off();  // still there: stay silent a while longer
    return;
  }
  if (state_ != ClaimState::kClaiming && state_ != ClaimState::kClaimed) return;
  if (!repeated) {
    // Once: contend. Our claim tells every node (the task controller included) which address our NAME
    // holds, and a second unit with our NAME, seeing it, answers in turn.
    queue({address_, name_}, now);
    return;
  }
  // Again within the window: two units share the NAME and cannot be told apart, so this one holds no
  // address for a while. Its cannot-claim (our NAME from 0xFE) makes the other unit do the same.
  ++hold_offs_;
  ++counters_.duplicate_name_holds;
  state_ = ClaimState::kCannotClaim;
  address_ = kNullAddress;
  reclaim_at_ = now + hold_off();
  queue({kNullAddress, name_}, now + cannot_claim_delay());
}

void AddressClaim::on_request_for_claim(Nanoseconds now) {
  switch (state_) {
    case ClaimState::kClaiming:
    case ClaimState::kClaimed:
      queue({address_, name_}, now);
      return;
    case ClaimState::kCannotClaim:
      queue({kNullAddress, name_}, now + cannot_claim_delay());
      return;
    case ClaimState::kNotStarted:
      return;
  }
}

void AddressClaim::on_address_violation(Nanoseconds now) {
  if (state_ != ClaimState::kClaiming && state_ != ClaimState::kClaimed) return;
  ++counters_.address_violations;
  // ISO 11783-5 (address violation): the holder answers a frame sent from its address with its claim, so
  // that the offender learns the address is taken and other nodes keep the right NAME for it.
  if (last_violation_claim_ && now - *last_violation_claim_ < kClaimSettleTime) return;
  last_violation_claim_ = now;
  ++counters_.violation_claims;
  queue({address_, name_}, now);
}

std::vector<ClaimMessage> AddressClaim::poll(Nanoseconds now) {
  if (state_ == ClaimState::kClaiming && now - claim_sent_at_ >= kClaimSettleTime) state_ = ClaimState::kClaimed;
  if (reclaim_at_ && now >= *reclaim_at_ && state_ == ClaimState::kCannotClaim) {
    // The hold-off after a duplicate NAME is over: start again from the preferred address.
    reclaim_at_.reset();
    if (preferred_ < kNullAddress) {
      claim(preferred_, now);
    } else {
      lose(now);
    }
  }
  if (state_ == ClaimState::kClaimed && hold_offs_ > 0 && last_own_name_ &&
      now - *last_own_name_ >= kDuplicateNameForgetAfter) {
    hold_offs_ = 0;
  }
  std::vector<ClaimMessage> due;
  // Stable: equal due times keep their queueing order.
  std::stable_sort(pending_.begin(), pending_.end(), [](const Pending& a, const Pending& b) { return a.due < b.due; });
  auto it = pending_.begin();
  for (; it != pending_.end() && it->due <= now; ++it) {
    // A message queued for an address we no longer hold is stale (we lost it meanwhile).
    if (it->message.source != kNullAddress && it->message.source != address_) continue;
    if (it->message.source == kNullAddress && state_ != ClaimState::kCannotClaim) continue;
    due.push_back(it->message);
    if (it->message.source == kNullAddress) {
      ++counters_.cannot_claim_sent;
    } else {
      ++counters_.claims_sent;
    }
  }
  pending_.erase(pending_.begin(), it);
  return due;
}

}  // namespace spread::isobus

#pragma once
// A stand-in for the slave's mailbox firmware while the real CoE module is being written: it sits
// on a real ESC's PDI (the way firmware does), takes requests from SM0 and answers in SM1 after
// ETG.1000.6, from a small dictionary. Written from the specification independently of the
// client under test; the master tests run against the real CoE module once it lands.
//
// Supports: SDO upload/download (expedited, normal, segmented with toggle check), complete access
// (subindex 0 padded to 16 bits), aborts (no object, no subindex, read-only, toggle), SDO info
// (OD list, object/entry description) fragmented to the mailbox size, queued emergencies, the
// repeat request (re-sends the last reply, toggles the acknowledge bit).
#include <algorithm>
#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "esc_model/esc.hpp"

namespace vdrive::master::test {

class CoeTestServer {
public:
  struct Entry {
    std::vector<std::uint8_t> value;
    bool writable = true;
    std::string name;
  };
  struct Object {
    std::string name;
    std::uint8_t object_code = 7;   // VAR
    std::map<std::uint8_t, Entry> entries;
  };
  std::map<std::uint16_t, Object> dictionary;
  std::uint64_t requests = 0;
  std::uint64_t repeats = 0;        // repeat requests served

  explicit CoeTestServer(esc::Esc& esc) : esc_(esc) {}

  void queue_emergency(std::uint16_t code, std::uint8_t reg) {
    std::vector<std::uint8_t> m{0, 0x10, static_cast<std::uint8_t>(code), static_cast<std::uint8_t>(code >> 8), reg, 1, 2, 3, 4, 5};
    out_.push_back(std::move(m));
  }

  // Call after the network ran: serves SM0, fills SM1.
  void service() {
    const std::uint16_t sm0_start = u16reg(0x0800), sm0_len = u16reg(0x0802);
    const std::uint16_t sm1_start = u16reg(0x0808), sm1_len = u16reg(0x080A);
    if (!(pdi8(0x0806) & 1) || !(pdi8(0x080E) & 1) || sm0_len < 8 || sm1_len < 8) return;
    tx_size_ = sm1_len;
    // Repeat request: 0x080E bit 1 differs from our acknowledge 0x080F bit 1.
    const std::uint8_t ack = pdi8(0x080F);
    if (((pdi8(0x080E) ^ ack) & 0x02) != 0) {
      ++repeats;
      if (!last_.empty() && !(pdi8(0x080D) & 0x08)) write_sm1(sm1_start, last_);
      const std::uint8_t v = static_cast<std::uint8_t>(ack ^ 0x02);
      esc_.pdi_write(0x080F, std::span(&v, 1));
    }
    if (pdi8(0x0805) & 0x08) {
      std::vector<std::uint8_t> buf(sm0_len);
      esc_.pdi_read(sm0_start, buf);
      const std::size_t len = std::min<std::size_t>(buf[0] | (buf[1] << 8), sm0_len - 6u);
      if ((buf[5] & 0x0F) == 3) handle(std::vector<std::uint8_t>(buf.begin() + 6, buf.begin() + 6 + static_cast<long>(len)));
      else out_.push_back({});  // a mailbox error reply is built below from an empty marker
    }
    if (!out_.empty() && !(pdi8(0x080D) & 0x08)) {
      std::vector<std::uint8_t> msg(sm1_len, 0);
      const auto& payload = out_.front();
      const bool error = payload.empty();
      const std::vector<std::uint8_t> body = error ? std::vector<std::uint8_t>{0x01, 0x00, 0x02, 0x00} : payload;
      msg[0] = static_cast<std::uint8_t>(body.size());
      msg[1] = static_cast<std::uint8_t>(body.size() >> 8);
      counter_ = static_cast<std::uint8_t>(counter_ % 7 + 1);
      msg[5] = static_cast<std::uint8_t>((error ? 0 : 3) | (counter_ << 4));
      std::copy(body.begin(), body.end(), msg.begin() + 6);
      out_.pop_front();
      last_ = msg;
      write_sm1(sm1_start, msg);
    }
  }

  std::size_t tx_size() const { return tx_size_; }

private:
  std::uint8_t pdi8(std::uint16_t a) {
    std::uint8_t v = 0;
    esc_.pdi_read(a, std::span(&v, 1));
    return v;
  }
  std::uint16_t u16reg(std::uint16_t a) { return static_cast<std::uint16_t>(pdi8(a) | (pdi8(a + 1) << 8)); }
  void write_sm1(std::uint16_t start, const std::vector<std::uint8_t>& msg) { esc_.pdi_write(start, msg); }

  static std::uint32_t u32(const std::vector<std::uint8_t>& p, std::size_t at) {
    return static_cast<std::uint32_t>(p[at] | (p[at + 1] << 8) | (p[at + 2] << 16)) | (static_cast<std::uint32_t>(p[at + 3]) << 24);
  }
  std::size_t room() const { return tx_size_ - 6; }

  void abort(std::uint16_t index, std::uint8_t sub, std::uint32_t code) {
    out_.push_back({0, 0x30, 0x80, static_cast<std::uint8_t>(index), static_cast<std::uint8_t>(index >> 8), sub,
                    static_cast<std::uint8_t>(code), static_cast<std::uint8_t>(code >> 8), static_cast<std::uint8_t>(code >> 16),
                    static_cast<std::uint8_t>(code >> 24)});
    transfer_.clear();
  }

  std::vector<std::uint8_t> object_bytes(const Object& o, std::uint8_t from) {
    std::vector<std::uint8_t> v;
    for (const auto& [sub, e] : o.entries) {
      if (sub < from) continue;
      v.insert(v.end(), e.value.begin(), e.value.end());
      if (sub == 0) v.push_back(0);  // subindex 0 padded to 16 bits
    }
    return v;
  }

  void handle(const std::vector<std::uint8_t>& m) {
    ++requests;
    if (m.size() < 3) return;
    const int service = m[1] >> 4;
    if (service == 8) return info(m);
    if (service != 2) return;
    const std::uint8_t cmd = m[2];
    const int ccs = cmd >> 5;
    if (ccs == 2 || ccs == 1) {  // initiate upload / download
      if (m.size() < 10) return;
      index_ = static_cast<std::uint16_t>(m[3] | (m[4] << 8));
      sub_ = m[5];
      const bool ca = cmd & 0x10;
      auto obj = dictionary.find(index_);
      if (obj == dictionary.end()) return abort(index_, sub_, 0x06020000);
      if (!ca && !obj->second.entries.count(sub_)) return abort(index_, sub_, 0x06090011);
      if (ccs == 2) return start_upload(obj->second, ca);
      return start_download(obj->second, ca, m);
    }
    if (ccs == 3) {  // upload segment
      if (((cmd & 0x10) != 0) != toggle_) return abort(index_, sub_, 0x05030000);
      const std::size_t n = std::min(room() - 3, transfer_.size() - sent_);
      std::vector<std::uint8_t> r{0, 0x30, 0};
      r.insert(r.end(), transfer_.begin() + static_cast<long>(sent_), transfer_.begin() + static_cast<long>(sent_ + n));
      const std::size_t unused = n < 7 ? 7 - n : 0;
      r.resize(3 + n + unused, 0);
      sent_ += n;
      r[2] = static_cast<std::uint8_t>((toggle_ ? 0x10 : 0) | (unused << 1) | (sent_ == transfer_.size() ? 1 : 0));
      toggle_ = !toggle_;
      out_.push_back(std::move(r));
      return;
    }
    if (ccs == 0) {  // download segment
      if (((cmd & 0x10) != 0) != toggle_) return abort(index_, sub_, 0x05030000);
      std::size_t n = m.size() - 3;
      if (m.size() == 10) n = 7 - ((cmd >> 1) & 7);
      transfer_.insert(transfer_.end(), m.begin() + 3, m.begin() + 3 + static_cast<long>(n));
      out_.push_back({0, 0x30, static_cast<std::uint8_t>(0x20 | (toggle_ ? 0x10 : 0)), 0, 0, 0, 0, 0, 0, 0});
      toggle_ = !toggle_;
      if (cmd & 1) store();
    }
  }

  void start_upload(const Object& o, bool ca) {
    transfer_ = ca ? object_bytes(o, sub_) : o.entries.at(sub_).value;
    toggle_ = false;
    std::vector<std::uint8_t> r{0, 0x30, 0x40, static_cast<std::uint8_t>(index_), static_cast<std::uint8_t>(index_ >> 8), sub_, 0, 0, 0, 0};
    if (!ca && transfer_.size() <= 4) {
      r[2] = static_cast<std::uint8_t>(0x43 | ((4 - transfer_.size()) << 2));
      std::copy(transfer_.begin(), transfer_.end(), r.begin() + 6);
      out_.push_back(std::move(r));
      return;
    }
    r[2] = static_cast<std::uint8_t>(0x41 | (ca ? 0x10 : 0));
    const auto size = static_cast<std::uint32_t>(transfer_.size());
    for (int i = 0; i < 4; ++i) r[6 + i] = static_cast<std::uint8_t>(size >> (8 * i));
    sent_ = std::min(room() - 10, transfer_.size());
    r.insert(r.end(), transfer_.begin(), transfer_.begin() + static_cast<long>(sent_));
    out_.push_back(std::move(r));
  }

  void start_download(const Object& o, bool ca, const std::vector<std::uint8_t>& m) {
    ca_ = ca;
    if (!ca && !o.entries.at(sub_).writable) return abort(index_, sub_, 0x06010002);
    if (m[2] & 0x02) {  // expedited
      const std::size_t n = (m[2] & 1) ? 4 - ((m[2] >> 2) & 3) : 4;
      transfer_.assign(m.begin() + 6, m.begin() + 6 + static_cast<long>(n));
      total_ = n;
    } else {
      total_ = u32(m, 6);
      transfer_.assign(m.begin() + 10, m.end());
    }
    toggle_ = false;
    out_.push_back({0, 0x30, 0x60, static_cast<std::uint8_t>(index_), static_cast<std::uint8_t>(index_ >> 8), sub_, 0, 0, 0, 0});
    if (transfer_.size() >= total_) store();
  }

  void store() {
    transfer_.resize(total_);
    Object& o = dictionary[index_];
    if (!ca_) {
      o.entries[sub_].value = transfer_;
      return;
    }
    std::size_t at = 0;
    for (auto& [sub, e] : o.entries) {
      if (sub < sub_) continue;
      const std::size_t n = e.value.size();
      std::copy(transfer_.begin() + static_cast<long>(at), transfer_.begin() + static_cast<long>(at + n), e.value.begin());
      at += n + (sub == 0 ? 1 : 0);
    }
  }

  void info(const std::vector<std::uint8_t>& m) {
    const int op = m[2] & 0x7F;
    std::vector<std::uint8_t> data;
    const std::uint16_t index = m.size() >= 8 ? static_cast<std::uint16_t>(m[6] | (m[7] << 8)) : 0;
    auto error = [&](std::uint32_t code) {
      out_.push_back({0, 0x80, 7, 0, 0, 0, static_cast<std::uint8_t>(code), static_cast<std::uint8_t>(code >> 8),
                      static_cast<std::uint8_t>(code >> 16), static_cast<std::uint8_t>(code >> 24)});
    };
    if (op == 1) {
      data = {m[6], m[7]};
      for (const auto& [i, o] : dictionary) {
        data.push_back(static_cast<std::uint8_t>(i));
        data.push_back(static_cast<std::uint8_t>(i >> 8));
      }
    } else if (op == 3) {
      auto o = dictionary.find(index);
      if (o == dictionary.end()) return error(0x06020000);
      const std::uint8_t max_sub = o->second.entries.rbegin()->first;
      data = {m[6], m[7], 0x07, 0x00, max_sub, o->second.object_code};
      data.insert(data.end(), o->second.name.begin(), o->second.name.end());
    } else if (op == 5) {
      auto o = dictionary.find(index);
      if (o == dictionary.end()) return error(0x06020000);
      auto e = o->second.entries.find(m[8]);
      if (e == o->second.entries.end()) return error(0x06090011);
      const auto bits = static_cast<std::uint16_t>(e->second.value.size() * 8);
      data = {m[6], m[7], m[8], 0, 0x07, 0x00, static_cast<std::uint8_t>(bits), static_cast<std::uint8_t>(bits >> 8),
              static_cast<std::uint8_t>(e->second.writable ? 0x3F : 0x07), 0};
      data.insert(data.end(), e->second.name.begin(), e->second.name.end());
    } else {
      return error(0x05040001);
    }
    // Fragments of at most the mailbox room minus the 6-byte info header.
    const std::size_t chunk = room() - 6;
    const std::size_t fragments = (data.size() + chunk - 1) / chunk;
    for (std::size_t f = 0; f < fragments; ++f) {
      const std::size_t left = fragments - 1 - f;
      std::vector<std::uint8_t> r{0, 0x80, static_cast<std::uint8_t>((op + 1) | (left ? 0x80 : 0)), 0,
                                  static_cast<std::uint8_t>(left), static_cast<std::uint8_t>(left >> 8)};
      const std::size_t from = f * chunk, to = std::min(data.size(), from + chunk);
      r.insert(r.end(), data.begin() + static_cast<long>(from), data.begin() + static_cast<long>(to));
      out_.push_back(std::move(r));
    }
  }

  esc::Esc& esc_;
  std::deque<std::vector<std::uint8_t>> out_;
  std::vector<std::uint8_t> last_, transfer_;
  std::size_t sent_ = 0, total_ = 0, tx_size_ = 0;
  std::uint16_t index_ = 0;
  std::uint8_t sub_ = 0, counter_ = 0;
  bool toggle_ = false, ca_ = false;
};

}  // namespace vdrive::master::test

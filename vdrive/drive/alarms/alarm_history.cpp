#include "vdrive/drive/alarms/alarm_history.hpp"

#include "vdrive/drive/alarms/diagnosis_history.hpp"
#include "vdrive/drive/alarms/xinje_alarm_history.hpp"

namespace vdrive::drive {

std::shared_ptr<AlarmHistory> make_alarm_history(HistoryKind kind, od::ObjectStore& store) {
  switch (kind) {
    case HistoryKind::DiagnosisHistory: {
      auto h = std::make_shared<DiagnosisHistory>(store);
      DiagnosisHistory::install_hook(h, store);
      return h;
    }
    case HistoryKind::XinjeMonitors: return std::make_shared<XinjeAlarmHistory>(store);
    case HistoryKind::None: break;
  }
  return nullptr;
}

}  // namespace vdrive::drive

#pragma once
// Optional real-time scheduling for irlocd on a robot.

namespace irloc::firmware {

// Switches the calling process to SCHED_FIFO at `priority` (1..99) and locks its memory, so
// page faults and ordinary processes cannot delay a frame. Throws io::InputError naming the
// cause when the system refuses (irlocd needs root or CAP_SYS_NICE and CAP_IPC_LOCK).
void enter_realtime(int priority);

}  // namespace irloc::firmware

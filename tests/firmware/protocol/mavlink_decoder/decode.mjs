// Independent MAVLink decoder for the irlocd tests: node-mavlink (its own CRC_EXTRA table and
// parser, not ours) reads the byte stream from file descriptor 3 (a pseudo-terminal master the
// test hands over) until the writer closes its end, and prints one line per decoded message:
//   HEARTBEAT seq sysid compid type autopilot base_mode custom_mode system_status mavlink_version arrival_ms
//   VPE seq sysid compid payload_length usec x y z roll pitch yaw cov0..cov20 reset_counter
//   STATUSTEXT seq sysid compid severity id chunk_seq "text" (JSON)
//   TIMESYNC seq sysid compid tc1 ts1 target_system target_component
//   ORIGIN seq sysid compid latitude longitude altitude target_system time_usec
//   ODOMETRY seq sysid compid payload_length time_usec x y z q0..q3 vx vy vz rollspeed pitchspeed
//            yawspeed pose_cov0..20 velocity_cov0..20 frame_id child_frame_id reset_counter
//            estimator_type quality
//   END valid=N invalid=N unknown=N crc_errors=N
// With `--timesync TS1`, it also sends a TIMESYNC request (tc1 0, ts1 TS1, from system 255,
// component 190, serialized by node-mavlink) to fd 3 after the first HEARTBEAT it reads.
import fs from 'node:fs'
import { MavLinkPacketSplitter, MavLinkPacketParser, MavLinkProtocolV2, minimal, common } from 'node-mavlink'

const timesyncAt = process.argv.indexOf('--timesync')
const timesyncTs1 = timesyncAt > 0 ? BigInt(process.argv[timesyncAt + 1]) : null
let timesyncSent = false

const registry = { ...minimal.REGISTRY, ...common.REGISTRY }
let crcErrors = 0
const splitter = new MavLinkPacketSplitter({}, { onCrcError: () => { crcErrors += 1 } })
const parser = new MavLinkPacketParser()
const input = fs.createReadStream(null, { fd: 3, highWaterMark: 256 })
const lines = []

parser.on('data', packet => {
  const header = packet.header
  const clazz = registry[header.msgid]
  if (!clazz) return
  const data = packet.protocol.data(packet.payload, clazz)
  const head = [header.seq, header.sysid, header.compid]
  if (header.msgid === minimal.Heartbeat.MSG_ID) {
    lines.push(['HEARTBEAT', ...head, data.type, data.autopilot, data.baseMode, data.customMode,
                data.systemStatus, data.mavlinkVersion, Date.now()].join(' '))
    if (timesyncTs1 !== null && !timesyncSent) {
      timesyncSent = true
      const request = new common.TimeSync()
      request.tc1 = 0n
      request.ts1 = timesyncTs1
      fs.writeSync(3, new MavLinkProtocolV2(255, 190).serialize(request, 0))
    }
  } else if (header.msgid === common.StatusText.MSG_ID) {
    lines.push(['STATUSTEXT', ...head, data.severity, data.id, data.chunkSeq, JSON.stringify(data.text)].join(' '))
  } else if (header.msgid === common.TimeSync.MSG_ID) {
    lines.push(['TIMESYNC', ...head, data.tc1.toString(), data.ts1.toString(), data.targetSystem,
                data.targetComponent].join(' '))
  } else if (header.msgid === common.SetGpsGlobalOrigin.MSG_ID) {
    lines.push(['ORIGIN', ...head, data.latitude, data.longitude, data.altitude, data.targetSystem,
                data.timeUsec.toString()].join(' '))
  } else if (header.msgid === common.Odometry.MSG_ID) {
    lines.push(['ODOMETRY', ...head, header.payloadLength, data.timeUsec.toString(), data.x, data.y, data.z, ...data.q,
                data.vx, data.vy, data.vz, data.rollspeed, data.pitchspeed, data.yawspeed, ...data.poseCovariance,
                ...data.velocityCovariance, data.frameId, data.childFrameId, data.resetCounter, data.estimatorType,
                data.quality].join(' '))
  } else if (header.msgid === common.VisionPositionEstimate.MSG_ID) {
    lines.push(['VPE', ...head, header.payloadLength, data.usec.toString(), data.x, data.y, data.z,
                data.roll, data.pitch, data.yaw, ...data.covariance, data.resetCounter].join(' '))
  }
})

const finish = () => {
  lines.push(`END valid=${splitter.validPackages} invalid=${splitter.invalidPackages} ` +
             `unknown=${splitter.unknownPackagesCount} crc_errors=${crcErrors}`)
  process.stdout.write(lines.join('\n') + '\n')
}

// A pty master reports EIO once the last slave descriptor is closed: that is the end.
input.on('error', error => {
  if (error.code !== 'EIO') throw error
  splitter.end()
})
input.pipe(splitter, { end: false })
input.on('end', () => splitter.end())
splitter.pipe(parser)
parser.on('finish', finish)

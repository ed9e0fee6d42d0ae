// Independent MAVLink decoder for the irlocd tests: node-mavlink (its own CRC_EXTRA table and
// parser, not ours) reads the byte stream from file descriptor 3 (a pseudo-terminal master the
// test hands over) until the writer closes its end, and prints one line per decoded message:
//   HEARTBEAT seq sysid compid type autopilot base_mode custom_mode system_status mavlink_version
//   VPE seq sysid compid payload_length usec x y z roll pitch yaw cov0..cov20 reset_counter
//   END valid=N invalid=N unknown=N crc_errors=N
import fs from 'node:fs'
import { MavLinkPacketSplitter, MavLinkPacketParser, minimal, common } from 'node-mavlink'

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
                data.systemStatus, data.mavlinkVersion].join(' '))
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

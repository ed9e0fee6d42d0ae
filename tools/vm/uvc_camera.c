// make test-vm's UVC camera: a USB video class device (UVC 1.0, one YUYV frame size, bulk
// streaming) emulated on the host and plugged into the guest through qemu's usb-redir device on
// its emulated xHCI controller (usbredir protocol, this program the usb-host side, over a unix
// socket), so that the guest's uvcvideo driver and libcamera's uvcvideo pipeline handler drive it
// as they drive a webcam. It lists the controls libcamera 0.4's uvcvideo handler maps to AeEnable,
// ExposureTime and AnalogueGain (the camera terminal's auto-exposure mode and absolute exposure
// time, the processing unit's gain) and writes each value the guest sets to the control log: what
// reaches a webcam's firmware. The frames are the given PGM images in order (looping), each as
// YUYV with the image as its luma, at most 30 a second. It serves one connection after another
// (one per boot) until killed.
// Usage: uvc_camera FRAME_LIST CONTROL_LOG SOCKET   (FRAME_LIST: one PGM path a line)
#include <errno.h>
#include <poll.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <time.h>
#include <unistd.h>
#include <usbredirparser.h>

enum { PAYLOAD_BYTES = 16384 };  // the bulk endpoint's 512 bytes x uvcvideo's 32 packets: one URB
enum { FRAME_INTERVAL_100NS = 333333 };

struct control {  // one UVC control: entity, selector, size, range and current value
  const char* name;
  int entity, selector, size;
  int32_t min, max, res, def, cur;
};

static struct control controls[] = {
    {"ae_mode", 1, 0x02, 1, 1, 2, 0x03, 1, 1},  // res: the modes offered (manual 1, auto 2)
    {"exposure_time_absolute", 1, 0x04, 4, 1, 10000, 1, 100, 100},  // 100 us units
    {"gain", 2, 0x04, 2, 100, 400, 1, 100, 100},
};

static int width, height, frame_count;
static uint8_t** frames;  // the images' pixels
static FILE* control_log;
static struct {
  int frame, fid;
  size_t offset;  // in the frame's YUYV bytes
  struct timespec due;
} stream;  // the video stream: its frame, frame ID bit, bytes of the frame sent, next frame's time

static void die(const char* what) {
  fprintf(stderr, "uvc_camera: %s: %s\n", what, errno ? strerror(errno) : "bad input");
  exit(1);
}

static void put16(uint8_t* p, unsigned v) { p[0] = v & 0xff; p[1] = (v >> 8) & 0xff; }
static void put32(uint8_t* p, uint32_t v) { put16(p, v & 0xffff); put16(p + 2, v >> 16); }

static uint8_t* read_pgm(const char* path) {
  FILE* file = fopen(path, "rb");
  int w, h, maxval;
  if (!file || fscanf(file, "P5 %d %d %d", &w, &h, &maxval) != 3 || maxval != 255 || fgetc(file) == EOF) die(path);
  if (width && (w != width || h != height)) die(path);
  width = w;
  height = h;
  uint8_t* pixels = malloc((size_t)w * h);
  if (!pixels || fread(pixels, 1, (size_t)w * h, file) != (size_t)w * h) die(path);
  fclose(file);
  return pixels;
}

static void read_frames(const char* list_path) {
  FILE* list = fopen(list_path, "r");
  char path[4096];
  if (!list) die(list_path);
  while (fscanf(list, "%4095s", path) == 1) {
    frames = realloc(frames, sizeof *frames * (frame_count + 1));
    if (!frames) die("memory");
    frames[frame_count++] = read_pgm(path);
  }
  fclose(list);
  if (frame_count == 0) die(list_path);
}

// The configuration descriptor with the video control and streaming interfaces' descriptors.
static int config_descriptor(uint8_t* d) {
  static const uint8_t yuy2[16] = {'Y', 'U', 'Y', '2', 0, 0, 0x10, 0, 0x80, 0, 0, 0xaa, 0, 0x38, 0x9b, 0x71};
  const uint32_t bitrate = (uint32_t)width * height * 16 * 30, frame_bytes = (uint32_t)width * height * 2;
  uint8_t* p = d;
  const uint8_t config[] = {9, 2, 0, 0, 2, 1, 0, 0x80, 250};
  const uint8_t association[] = {8, 0x0b, 0, 2, 0x0e, 0x03, 0, 0};
  const uint8_t control_interface[] = {9, 4, 0, 0, 0, 0x0e, 0x01, 0, 0};
  uint8_t control_header[] = {13, 0x24, 0x01, 0x00, 0x01, 51, 0, 0x00, 0x6c, 0xdc, 0x02, 1, 1};
  // Camera terminal 1: auto-exposure mode (bit 1), absolute exposure time (bit 3).
  const uint8_t camera[] = {18, 0x24, 0x02, 1, 0x01, 0x02, 0, 0, 0, 0, 0, 0, 0, 0, 3, 0x0a, 0, 0};
  const uint8_t processing[] = {11, 0x24, 0x05, 2, 1, 0, 0, 2, 0x00, 0x02, 0};  // unit 2: gain (bit 9)
  const uint8_t output[] = {9, 0x24, 0x03, 3, 0x01, 0x01, 0, 2, 0};
  const uint8_t streaming_interface[] = {9, 4, 1, 0, 1, 0x0e, 0x02, 0, 0};
  const uint8_t input_header[] = {14, 0x24, 0x01, 1, 71, 0, 0x81, 0, 3, 0, 0, 0, 1, 0};
  uint8_t format[27] = {27, 0x24, 0x04, 1, 1};
  memcpy(format + 5, yuy2, 16);
  format[21] = 16;
  format[22] = 1;
  uint8_t frame[30] = {30, 0x24, 0x05, 1, 0};
  put16(frame + 5, width);
  put16(frame + 7, height);
  put32(frame + 9, bitrate);
  put32(frame + 13, bitrate);
  put32(frame + 17, frame_bytes);
  put32(frame + 21, FRAME_INTERVAL_100NS);
  frame[25] = 1;
  put32(frame + 26, FRAME_INTERVAL_100NS);
  const uint8_t endpoint[] = {7, 5, 0x81, 0x02, 0x00, 0x02, 0};
  const uint8_t* parts[] = {config, association, control_interface, control_header, camera, processing, output,
                            streaming_interface, input_header, format, frame, endpoint};
  for (size_t i = 0; i < sizeof parts / sizeof *parts; ++i) {
    memcpy(p, parts[i], parts[i][0]);
    p += parts[i][0];
  }
  put16(d + 2, p - d);
  return p - d;
}

static int device_descriptor(uint8_t* d) {
  const uint8_t device[18] = {18, 1, 0x00, 0x02, 0xef, 0x02, 0x01, 64, 0x09, 0x12, 0x01, 0x00, 0x00, 0x01, 0, 0, 0, 1};
  memcpy(d, device, sizeof device);
  return sizeof device;
}

// The streaming parameters (UVC 1.0's 26 bytes): always the one format, frame size and rate.
static int streaming_parameters(uint8_t* d) {
  memset(d, 0, 26);
  d[2] = 1;  // format index
  d[3] = 1;  // frame index
  put32(d + 4, FRAME_INTERVAL_100NS);
  put32(d + 18, (uint32_t)width * height * 2);
  put32(d + 22, PAYLOAD_BYTES);
  return 26;
}

static struct control* find_control(int entity, int selector) {
  for (size_t i = 0; i < sizeof controls / sizeof *controls; ++i) {
    if (controls[i].entity == entity && controls[i].selector == selector) return &controls[i];
  }
  return NULL;
}

// A class request's answer into `d` (its length), or -1: stall.
static int class_request(const uint8_t* setup, const uint8_t* data, int length, uint8_t* d) {
  const int request = setup[1], selector = setup[3], interface = setup[4], entity = setup[5];
  enum { SET_CUR = 0x01, GET_CUR = 0x81, GET_MIN, GET_MAX, GET_RES, GET_LEN, GET_INFO, GET_DEF };
  if (interface == 1 && (selector == 1 || selector == 2)) {  // probe and commit
    if (request == SET_CUR && selector == 2) stream.offset = 0;  // a new stream: from a frame's start
    if (request == SET_CUR) return 0;
    if (request == GET_INFO) return d[0] = 0x03, 1;
    if (request == GET_LEN) return put16(d, 26), 2;
    return streaming_parameters(d);
  }
  struct control* control = interface == 0 ? find_control(entity, selector) : NULL;
  if (!control) return -1;
  int32_t value;
  switch (request) {
    case SET_CUR:
      if (length < control->size) return -1;
      control->cur = control->size == 1 ? data[0] : control->size == 2 ? data[0] | data[1] << 8
                                                  : (int32_t)(data[0] | data[1] << 8 | data[2] << 16 | (uint32_t)data[3] << 24);
      fprintf(control_log, "%s %d\n", control->name, control->cur);
      fflush(control_log);
      return 0;
    case GET_INFO: return d[0] = 0x03, 1;
    case GET_LEN: return put16(d, control->size), 2;
    case GET_CUR: value = control->cur; break;
    case GET_MIN: value = control->min; break;
    case GET_MAX: value = control->max; break;
    case GET_RES: value = control->res; break;
    case GET_DEF: value = control->def; break;
    default: return -1;
  }
  put32(d, (uint32_t)value);
  return control->size;
}

// A control transfer's answer into `d` (its length), or -1: stall.
static int control_request(const uint8_t* setup, const uint8_t* data, int length, uint8_t* d) {
  const int type = (setup[0] >> 5) & 3, request = setup[1], descriptor = setup[3];
  if (type == 1) return class_request(setup, data, length, d);
  if (type != 0) return -1;
  switch (request) {
    case 0x06:  // GET_DESCRIPTOR
      if (descriptor == 1) return device_descriptor(d);
      if (descriptor == 2) return config_descriptor(d);
      return -1;
    case 0x00: return put16(d, 0), 2;  // GET_STATUS
    case 0x08: return d[0] = 1, 1;     // GET_CONFIGURATION
    case 0x0a: return d[0] = 0, 1;     // GET_INTERFACE
    default: return 0;                 // SET_CONFIGURATION, SET_INTERFACE, CLEAR/SET_FEATURE
  }
}

// The next bulk payload of the stream: a 2-byte header (frame ID, end of frame) and YUYV bytes;
// a frame starts at least one frame interval after the one before (at most 30 per second).
static int next_payload(uint8_t* d, int room) {
  int frame = stream.frame, fid = stream.fid;
  size_t offset = stream.offset;
  struct timespec due = stream.due;
  const size_t frame_bytes = (size_t)width * height * 2;
  if (offset == 0) {
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    if (now.tv_sec > due.tv_sec || (now.tv_sec == due.tv_sec && now.tv_nsec > due.tv_nsec)) due = now;
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &due, NULL);
    due.tv_nsec += FRAME_INTERVAL_100NS * 100L;
    if (due.tv_nsec >= 1000000000L) due.tv_sec += 1, due.tv_nsec -= 1000000000L;
  }
  const size_t bytes = frame_bytes - offset < (size_t)room - 2 ? frame_bytes - offset : (size_t)room - 2;
  const uint8_t* image = frames[frame];
  for (size_t i = 0; i < bytes; ++i) {
    const size_t at = offset + i;
    d[2 + i] = at % 2 == 0 ? image[at / 2] : 128;
  }
  offset += bytes;
  d[0] = 2;
  d[1] = 0x80 | fid | (offset == frame_bytes ? 0x02 : 0);
  if (offset == frame_bytes) {
    offset = 0;
    fid ^= 1;
    frame = (frame + 1) % frame_count;
  }
  stream.frame = frame, stream.fid = fid, stream.offset = offset, stream.due = due;
  return (int)(2 + bytes);
}

static int connection;  // qemu's, non-blocking: usbredirparser reads until nothing is left
static struct usbredirparser* parser;

static int read_cb(void* priv, uint8_t* data, int count) {
  (void)priv;
  const int r = (int)read(connection, data, (size_t)count);
  if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return 0;
  return r == 0 ? -1 : r;
}
static int write_cb(void* priv, uint8_t* data, int count) {
  (void)priv;
  const int r = (int)write(connection, data, (size_t)count);
  return r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) ? 0 : r;
}
static void log_cb(void* priv, int level, const char* msg) { (void)priv; if (level <= usbredirparser_warning) fprintf(stderr, "usbredir: %s\n", msg); }

// qemu's usb-redir has said hello: the device is plugged in (its interfaces, its endpoints, indexed
// by direction bit x 16 + number, then the device itself, high speed).
static void hello_cb(void* priv, struct usb_redir_hello_header* hello) {
  (void)priv; (void)hello;
  struct usb_redir_interface_info_header interfaces = {0};
  interfaces.interface_count = 2;
  interfaces.interface[1] = 1;
  interfaces.interface_class[0] = interfaces.interface_class[1] = 0x0e;
  interfaces.interface_subclass[0] = 1;
  interfaces.interface_subclass[1] = 2;
  usbredirparser_send_interface_info(parser, &interfaces);
  struct usb_redir_ep_info_header endpoints;
  memset(&endpoints, 0, sizeof endpoints);
  memset(endpoints.type, usb_redir_type_invalid, sizeof endpoints.type);
  endpoints.type[0] = endpoints.type[16] = usb_redir_type_control;
  endpoints.max_packet_size[0] = endpoints.max_packet_size[16] = 64;
  endpoints.type[17] = usb_redir_type_bulk;
  endpoints.interface[17] = 1;
  endpoints.max_packet_size[17] = 512;
  usbredirparser_send_ep_info(parser, &endpoints);
  struct usb_redir_device_connect_header device = {usb_redir_speed_high, 0xef, 0x02, 0x01, 0x1209, 0x0001, 0x0100};
  usbredirparser_send_device_connect(parser, &device);
}

// A control transfer (qemu handles SET_ADDRESS and turns the configuration and interface requests
// into their own packets), answered at once.
static void control_cb(void* priv, uint64_t id, struct usb_redir_control_packet_header* header, uint8_t* data, int length) {
  (void)priv;
  static uint8_t answer[4096];
  const uint8_t setup[8] = {header->requesttype, header->request, header->value & 0xff, header->value >> 8,
                            header->index & 0xff, header->index >> 8, header->length & 0xff, header->length >> 8};
  const int in = header->requesttype & 0x80;
  const int answered = control_request(setup, data, length, answer);
  header->status = answered < 0 ? usb_redir_stall : usb_redir_success;
  if (in) {
    header->length = answered < 0 ? 0 : answered < header->length ? answered : header->length;
    usbredirparser_send_control_packet(parser, id, header, answer, header->length);
  } else {
    usbredirparser_send_control_packet(parser, id, header, NULL, 0);
  }
  if (data) usbredirparser_free_packet_data(parser, data);
}

// A bulk transfer: the streaming endpoint's next payload.
static void bulk_cb(void* priv, uint64_t id, struct usb_redir_bulk_packet_header* header, uint8_t* data, int length) {
  (void)priv; (void)length;
  static uint8_t answer[PAYLOAD_BYTES];
  const int wanted = header->length | header->length_high << 16;
  const int sent = next_payload(answer, wanted < PAYLOAD_BYTES ? wanted : PAYLOAD_BYTES);
  header->status = usb_redir_success;
  header->length = (uint16_t)sent;
  header->length_high = 0;
  usbredirparser_send_bulk_packet(parser, id, header, answer, sent);
  if (data) usbredirparser_free_packet_data(parser, data);
}

// One configuration, and one setting per interface: every choice is taken as made.
static void set_configuration_cb(void* priv, uint64_t id, struct usb_redir_set_configuration_header* header) {
  (void)priv;
  struct usb_redir_configuration_status_header status = {usb_redir_success, header->configuration};
  usbredirparser_send_configuration_status(parser, id, &status);
}
static void get_configuration_cb(void* priv, uint64_t id) {
  (void)priv;
  struct usb_redir_configuration_status_header status = {usb_redir_success, 1};
  usbredirparser_send_configuration_status(parser, id, &status);
}
static void set_alt_setting_cb(void* priv, uint64_t id, struct usb_redir_set_alt_setting_header* header) {
  (void)priv;
  struct usb_redir_alt_setting_status_header status = {usb_redir_success, header->interface, header->alt};
  usbredirparser_send_alt_setting_status(parser, id, &status);
}
static void get_alt_setting_cb(void* priv, uint64_t id, struct usb_redir_get_alt_setting_header* header) {
  (void)priv;
  struct usb_redir_alt_setting_status_header status = {usb_redir_success, header->interface, 0};
  usbredirparser_send_alt_setting_status(parser, id, &status);
}
static void cancel_cb(void* priv, uint64_t id) { (void)priv; (void)id; }  // nothing is pending
static void reset_cb(void* priv) { (void)priv; }

// One connection (one boot), until qemu closes it.
static void serve(void) {
  parser = usbredirparser_create();
  parser->log_func = log_cb;
  parser->read_func = read_cb;
  parser->write_func = write_cb;
  parser->hello_func = hello_cb;
  parser->control_packet_func = control_cb;
  parser->bulk_packet_func = bulk_cb;
  parser->set_configuration_func = set_configuration_cb;
  parser->get_configuration_func = get_configuration_cb;
  parser->set_alt_setting_func = set_alt_setting_cb;
  parser->get_alt_setting_func = get_alt_setting_cb;
  parser->cancel_data_packet_func = cancel_cb;
  parser->reset_func = reset_cb;
  uint32_t caps[USB_REDIR_CAPS_SIZE] = {0};
  usbredirparser_caps_set_cap(caps, usb_redir_cap_connect_device_version);
  usbredirparser_caps_set_cap(caps, usb_redir_cap_ep_info_max_packet_size);
  usbredirparser_caps_set_cap(caps, usb_redir_cap_64bits_ids);
  usbredirparser_caps_set_cap(caps, usb_redir_cap_32bits_bulk_length);
  usbredirparser_init(parser, "irloc uvc camera", caps, USB_REDIR_CAPS_SIZE, usbredirparser_fl_usb_host);
  for (;;) {
    struct pollfd fd = {connection, POLLIN | (usbredirparser_has_data_to_write(parser) ? POLLOUT : 0), 0};
    if (poll(&fd, 1, -1) < 0) break;
    if ((fd.revents & POLLIN) && usbredirparser_do_read(parser) != 0) break;
    if ((fd.revents & POLLOUT) && usbredirparser_do_write(parser) != 0) break;
    if (fd.revents & (POLLHUP | POLLERR)) break;
  }
  usbredirparser_destroy(parser);
}

int main(int argc, char** argv) {
  if (argc != 4) { fprintf(stderr, "usage: redir_camera FRAME_LIST CONTROL_LOG SOCKET\n"); return 2; }
  read_frames(argv[1]);
  control_log = fopen(argv[2], "w");
  if (!control_log) die(argv[2]);
  int server = socket(AF_UNIX, SOCK_STREAM, 0);
  struct sockaddr_un address = {.sun_family = AF_UNIX};
  strncpy(address.sun_path, argv[3], sizeof address.sun_path - 1);
  unlink(argv[3]);
  if (bind(server, (struct sockaddr*)&address, sizeof address) != 0 || listen(server, 1) != 0) die(argv[3]);
  for (;;) {
    connection = accept4(server, NULL, NULL, SOCK_NONBLOCK);
    if (connection < 0) die("accept");
    stream.offset = 0;
    serve();
    close(connection);
  }
}

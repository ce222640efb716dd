# SPDX-License-Identifier: BSD-3-Clause
"""Reads the room bags back and checks them against datasets/room/room.sglog, independently of
the writers: it parses the sglog itself and decodes the ROS 2 CDR bytes itself.

    /usr/bin/python3 tests/data/bags/room/check_roundtrip.py [--node-modules DIR]

ROS 1 bags are read with python3-rosbag, the rosbag2 SQLite bag with python3's sqlite3, and, with
--node-modules (the folder make_ros2.mjs was run with), the MCAP files through check_mcap.mjs
(@mcap/core's reader). Without it the MCAP files are skipped.

Checked for every sglog-equivalent bag: the message counts (743 /odom, 743 /ground_truth, 11888
/sonar, 1 /tf_static), the order (/tf_static first, then per scan /odom, /ground_truth, the
scan's /sonar readings in file order), every stamp and log time (1700000000 s + the sglog time,
exactly), header.seq (ROS 1), frame ids, positions (exact doubles), the Range constants, and that
every float32 range, widened through its shortest decimal form, is the sglog's decimal exactly
(+inf for none). RosAria bag: 743 poses and 743 16-point clouds. Each yaw is recomputed with the
reader's formula; yaws that do not come back exactly are reported (they do not fail the check).
Exit status 1 if any other check fails.
"""

import argparse
import base64
import json
import math
import os
import sqlite3
import struct
import subprocess
import sys
from decimal import Decimal

import rosbag

HERE = os.path.dirname(os.path.abspath(__file__))
SGLOG = os.path.normpath(os.path.join(HERE, '..', '..', '..', '..', 'datasets', 'room', 'room.sglog'))
EPOCH = 1700000000


# ---- the sglog, parsed here again (no comments or odd spacing in room.sglog) ----

def load_sglog():
    header = {'sonars': []}
    scans = []
    with open(SGLOG, encoding='utf-8') as f:
        for line in f:
            f_ = line.split('#')[0].split() if not line.startswith('name ') else ['name']
            if not f_:
                continue
            if f_[0] in ('aperture', 'min_range', 'max_range'):
                header[f_[0]] = f_[1]
            elif f_[0] == 'sonar':
                header['sonars'].append(f_[2:5])
            elif f_[0] == 'scan':
                scans.append({'t': f_[1], 'pose': f_[2:5],
                              'truth': None if f_[5] == 'none' else f_[5:8], 'readings': []})
            elif f_[0] == 'r':
                scans[-1]['readings'].append((int(f_[1]), f_[2]))
    return header, scans


def ns_of(text):
    """EPOCH + the decimal time, in integer nanoseconds."""
    v = (Decimal(EPOCH) + Decimal(text)) * 1000000000
    assert v == v.to_integral_value(), text
    return int(v)


def shortest_f32(value):
    """The shortest decimal that reads back (rounded to float32) as the float32 VALUE."""
    if math.isinf(value):
        return value
    bits = struct.pack('<f', value)
    for digits in range(1, 10):
        text = '%.*g' % (digits, value)
        if struct.pack('<f', float(text)) == bits:
            return Decimal(text)
    raise AssertionError(value)


def f32(v):
    return struct.unpack('<f', struct.pack('<f', v))[0]


def yaw(q):
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), w * w + x * x - y * y - z * z)


# ---- a small CDR reader (XCDR1, as rosbag2 stores messages) ----

class Cdr:
    def __init__(self, data):
        if data[0] != 0 or data[1] not in (0, 1):
            raise ValueError('not a plain CDR encapsulation')
        self.e = '<' if data[1] == 1 else '>'
        self.b = data
        self.p = 4

    def _get(self, fmt, size):
        self.p += (-(self.p - 4)) % size
        (v,) = struct.unpack_from(self.e + fmt, self.b, self.p)
        self.p += size
        return v

    def u8(self):
        return self._get('B', 1)

    def i32(self):
        return self._get('i', 4)

    def u32(self):
        return self._get('I', 4)

    def f32(self):
        return self._get('f', 4)

    def f64(self):
        return self._get('d', 8)

    def string(self):
        n = self.u32()
        s = self.b[self.p:self.p + n]
        self.p += n
        assert s.endswith(b'\0')
        return s[:-1].decode()

    def header(self):
        sec = self.i32()
        nsec = self.u32()
        return {'ns': sec * 1000000000 + nsec, 'frame_id': self.string(), 'seq': None}

    def vec(self, n):
        return tuple(self.f64() for _ in range(n))

    def done(self):
        assert len(self.b) - self.p < 4, (len(self.b), self.p)  # at most padding left


def decode_cdr(type_, data):
    c = Cdr(data)
    if type_ == 'sensor_msgs/msg/Range':
        m = {'header': c.header(), 'radiation_type': c.u8(), 'field_of_view': c.f32(),
             'min_range': c.f32(), 'max_range': c.f32(), 'range': c.f32()}
    elif type_ == 'nav_msgs/msg/Odometry':
        m = {'header': c.header(), 'child_frame_id': c.string(), 'position': c.vec(3),
             'orientation': c.vec(4), 'pose_covariance': c.vec(36), 'twist': c.vec(6),
             'twist_covariance': c.vec(36)}
    elif type_ == 'geometry_msgs/msg/PoseStamped':
        m = {'header': c.header(), 'position': c.vec(3), 'orientation': c.vec(4)}
    elif type_ == 'tf2_msgs/msg/TFMessage':
        m = {'transforms': []}
        for _ in range(c.u32()):
            m['transforms'].append({'header': c.header(), 'child_frame_id': c.string(),
                                    'translation': c.vec(3), 'rotation': c.vec(4)})
    else:
        raise ValueError(type_)
    c.done()
    return m


# ---- ROS 1 messages in the same plain form ----

def plain_ros1(msg):
    def hdr(h):
        return {'ns': h.stamp.secs * 1000000000 + h.stamp.nsecs, 'frame_id': h.frame_id,
                'seq': h.seq}

    def v3(p):
        return (p.x, p.y, p.z)

    def q4(q):
        return (q.x, q.y, q.z, q.w)

    t = msg._type
    if t == 'sensor_msgs/Range':
        return {'header': hdr(msg.header), 'radiation_type': msg.radiation_type,
                'field_of_view': msg.field_of_view, 'min_range': msg.min_range,
                'max_range': msg.max_range, 'range': msg.range}
    if t == 'nav_msgs/Odometry':
        tw = msg.twist.twist
        return {'header': hdr(msg.header), 'child_frame_id': msg.child_frame_id,
                'position': v3(msg.pose.pose.position), 'orientation': q4(msg.pose.pose.orientation),
                'pose_covariance': tuple(msg.pose.covariance),
                'twist': v3(tw.linear) + v3(tw.angular),
                'twist_covariance': tuple(msg.twist.covariance)}
    if t == 'geometry_msgs/PoseStamped':
        return {'header': hdr(msg.header), 'position': v3(msg.pose.position),
                'orientation': q4(msg.pose.orientation)}
    if t == 'tf2_msgs/TFMessage':
        return {'transforms': [{'header': hdr(x.header), 'child_frame_id': x.child_frame_id,
                                'translation': v3(x.transform.translation),
                                'rotation': q4(x.transform.rotation)} for x in msg.transforms]}
    if t == 'sensor_msgs/PointCloud':
        return {'header': hdr(msg.header), 'points': [(p.x, p.y, p.z) for p in msg.points],
                'channels': len(msg.channels)}
    raise ValueError(t)


# ---- the checks ----

class Report:
    def __init__(self, name):
        self.name = name
        self.failures = []
        self.yaw_off = {}  # angle text -> messages
        self.checked = 0

    def fail(self, text):
        self.failures.append(text)

    def expect(self, ok, text):
        self.checked += 1
        if not ok:
            self.fail(text)

    def check_yaw(self, q, text, where):
        self.expect(q[0] == 0.0 and q[1] == 0.0, f'{where}: quaternion x, y not 0: {q}')
        if yaw(q) != float(text):
            self.yaw_off[text] = self.yaw_off.get(text, 0) + 1

    def print(self):
        status = 'FAILED' if self.failures else 'ok'
        print(f'{self.name}: {status} ({self.checked} checks, {len(self.failures)} failures)')
        for f in self.failures[:20]:
            print(f'  {f}')
        if len(self.failures) > 20:
            print(f'  ... {len(self.failures) - 20} more')
        if self.yaw_off:
            listed = ', '.join(f'{a} ({n}x)' for a, n in sorted(self.yaw_off.items()))
            print(f'  yaw not exact in {sum(self.yaw_off.values())} places: {listed}')


def check_equivalent(report, stream, header, scans, has_seq):
    """STREAM: (topic, log time ns, plain message, connection latching flag or None)."""
    msgs = list(stream)
    counts = {}
    for topic, _, _, _ in msgs:
        counts[topic] = counts.get(topic, 0) + 1
    want = {'/tf_static': 1, '/odom': len(scans),
            '/ground_truth': sum(1 for s in scans if s['truth']),
            '/sonar': sum(len(s['readings']) for s in scans)}
    report.expect(counts == want, f'message counts {counts}, expected {want}')
    print(f'  {report.name}: ' + ', '.join(f'{n} {t}' for t, n in counts.items()))
    seqs = {}

    def check_header(h, topic, ns, frame, where):
        report.expect(h['ns'] == ns, f'{where}: stamp {h["ns"]} ns, expected {ns}')
        report.expect(h['frame_id'] == frame, f'{where}: frame_id {h["frame_id"]!r}')
        if has_seq:
            report.expect(h['seq'] == seqs.get(topic, 0), f'{where}: seq {h["seq"]}')
        seqs[topic] = seqs.get(topic, 0) + 1

    it = iter(msgs)
    first_ns = ns_of(scans[0]['t'])
    topic, log, m, latching = next(it)
    report.expect(topic == '/tf_static', f'first message on {topic}')
    report.expect(log == first_ns, f'/tf_static log time {log}')
    if latching is not None:
        report.expect(latching == '1', f'/tf_static connection latching={latching!r}')
    report.expect(len(m['transforms']) == len(header['sonars']), '/tf_static transform count')
    for i, (tf, (x, y, th)) in enumerate(zip(m['transforms'], header['sonars'])):
        where = f'/tf_static sonar_{i}'
        report.expect(tf['header']['ns'] == first_ns and tf['header']['frame_id'] == 'base_link',
                      f'{where}: header {tf["header"]}')
        report.expect(tf['child_frame_id'] == f'sonar_{i}', f'{where}: child {tf["child_frame_id"]}')
        report.expect(tf['translation'] == (float(x), float(y), 0.0), f'{where}: translation')
        report.check_yaw(tf['rotation'], th, where)
    fov = f32(float(header['aperture']))
    rmin = f32(float(header['min_range']))
    rmax = f32(float(header['max_range']))
    bad_ranges = 0
    for k, scan in enumerate(scans):
        ns = ns_of(scan['t'])
        where = f'scan {k} (t={scan["t"]})'
        topic, log, m, _ = next(it)
        report.expect(topic == '/odom' and log == ns, f'{where}: expected /odom at {ns}, got {topic} at {log}')
        check_header(m['header'], '/odom', ns, 'odom', f'{where} /odom')
        report.expect(m['child_frame_id'] == 'base_link', f'{where} /odom child_frame_id')
        x, y, th = scan['pose']
        report.expect(m['position'] == (float(x), float(y), 0.0), f'{where} /odom position {m["position"]}')
        report.check_yaw(m['orientation'], th, f'{where} /odom')
        report.expect(not any(m['pose_covariance']) and not any(m['twist'])
                      and not any(m['twist_covariance']), f'{where} /odom twist or covariance not 0')
        if scan['truth']:
            topic, log, m, _ = next(it)
            report.expect(topic == '/ground_truth' and log == ns,
                          f'{where}: expected /ground_truth at {ns}, got {topic} at {log}')
            check_header(m['header'], '/ground_truth', ns, 'map', f'{where} /ground_truth')
            x, y, th = scan['truth']
            report.expect(m['position'] == (float(x), float(y), 0.0), f'{where} /ground_truth position')
            report.check_yaw(m['orientation'], th, f'{where} /ground_truth')
        for sonar, text in scan['readings']:
            topic, log, m, _ = next(it)
            w = f'{where} sonar {sonar}'
            report.expect(topic == '/sonar' and log == ns, f'{w}: expected /sonar at {ns}, got {topic} at {log}')
            check_header(m['header'], '/sonar', ns, f'sonar_{sonar}', w)
            report.expect((m['radiation_type'], m['field_of_view'], m['min_range'], m['max_range'])
                          == (0, fov, rmin, rmax), f'{w}: Range constants {m}')
            got = shortest_f32(m['range'])
            expected = math.inf if text == 'none' else Decimal(text)
            if got != expected:
                bad_ranges += 1
            report.expect(got == expected, f'{w}: range {m["range"]!r} reads as {got}, sglog {text}')
    report.expect(next(it, None) is None, 'messages after the last reading')
    print(f'  {report.name}: {want["/sonar"] - bad_ranges} of {want["/sonar"]} ranges give back '
          f'the sglog decimal through their shortest float32 form')


def ros1_stream(path):
    with rosbag.Bag(path) as bag:
        for topic, msg, t, conn in bag.read_messages(return_connection_header=True):
            latching = conn.get('latching', b'0')
            if isinstance(latching, bytes):
                latching = latching.decode()
            yield topic, t.secs * 1000000000 + t.nsecs, plain_ros1(msg), latching


def check_rosaria(report, path, header, scans):
    msgs = list(ros1_stream(path))
    counts = {}
    for topic, _, _, _ in msgs:
        counts[topic] = counts.get(topic, 0) + 1
    want = {'/RosAria/pose': len(scans), '/RosAria/sonar': len(scans)}
    report.expect(counts == want, f'message counts {counts}, expected {want}')
    print(f'  {report.name}: ' + ', '.join(f'{n} {t}' for t, n in counts.items()))
    sonars = [tuple(float(v) for v in s) for s in header['sonars']]
    for k, scan in enumerate(scans):
        ns = ns_of(scan['t'])
        (t1, l1, pose, _), (t2, l2, cloud, _) = msgs[2 * k], msgs[2 * k + 1]
        where = f'scan {k}'
        report.expect((t1, l1, t2, l2) == ('/RosAria/pose', ns, '/RosAria/sonar', ns), f'{where}: order/times')
        report.expect(pose['header']['ns'] == ns and pose['header']['seq'] == k, f'{where}: pose header')
        report.expect(pose['position'] == (float(scan['pose'][0]), float(scan['pose'][1]), 0.0),
                      f'{where}: pose position')
        report.check_yaw(pose['orientation'], scan['pose'][2], f'{where} pose')
        report.expect(cloud['header'] == {'ns': ns, 'frame_id': 'base_link', 'seq': k}, f'{where}: cloud header')
        report.expect(len(cloud['points']) == 16 and cloud['channels'] == 0, f'{where}: cloud size')
        ranges = dict(scan['readings'])
        for i, (p, (x, y, th)) in enumerate(zip(cloud['points'], sonars)):
            r = 5.0 if ranges[i] == 'none' else float(ranges[i])
            expected = (f32(x + r * math.cos(th)), f32(y + r * math.sin(th)), 0.0)
            report.expect(p == expected, f'{where} point {i}: {p}, expected {expected}')


def sqlite_stream(path):
    db = sqlite3.connect(f'file:{path}?mode=ro', uri=True)
    topics = {i: (name, type_, fmt) for i, name, type_, fmt in
              db.execute('SELECT id, name, type, serialization_format FROM topics')}
    for topic_id, ts, data in db.execute('SELECT topic_id, timestamp, data FROM messages ORDER BY id'):
        name, type_, fmt = topics[topic_id]
        assert fmt == 'cdr'
        yield name, ts, decode_cdr(type_, bytes(data)), None
    db.close()


def mcap_stream(path, modules, report):
    out = subprocess.run(['node', os.path.join(HERE, 'check_mcap.mjs'), modules, path],
                         check=True, capture_output=True, text=True).stdout
    schemas, channels = {}, {}
    for line in out.splitlines():
        o = json.loads(line)
        if 'schema' in o:
            report.expect(o['encoding'] == 'ros2msg', f'schema {o["name"]} encoding {o["encoding"]}')
            schemas[o['schema']] = o['name']
        elif 'channel' in o:
            report.expect(o['messageEncoding'] == 'cdr', f'channel {o["topic"]} encoding')
            report.expect('offered_qos_profiles' in o['metadata'], f'channel {o["topic"]} has no QoS')
            channels[o['channel']] = (o['topic'], schemas[o['schemaId']])
        elif 'header' in o:
            print(f'  {report.name}: profile {o["header"]["profile"]!r}, chunks {o["chunks"]}')
        elif 'statistics' in o:
            report.expect(o['statistics']['messageCount'] == '13375', f'statistics {o["statistics"]}')
        else:
            topic, type_ = channels[o['channelId']]
            report.expect(o['logTime'] == o['publishTime'], 'publish time differs from log time')
            yield topic, int(o['logTime']), decode_cdr(type_, base64.b64decode(o['data'])), None


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--node-modules', help="make_ros2.mjs's node_modules folder (MCAP check)")
    args = parser.parse_args()
    header, scans = load_sglog()
    reports = []
    for name in ('room-none.bag', 'room-bz2.bag', 'room-lz4.bag'):
        r = Report(name)
        check_equivalent(r, ros1_stream(os.path.join(HERE, name)), header, scans, True)
        reports.append(r)
    r = Report('rosaria-room.bag')
    check_rosaria(r, os.path.join(HERE, 'rosaria-room.bag'), header, scans)
    reports.append(r)
    r = Report('room-sqlite/room-sqlite_0.db3')
    check_equivalent(r, sqlite_stream(os.path.join(HERE, 'room-sqlite', 'room-sqlite_0.db3')),
                     header, scans, False)
    reports.append(r)
    if args.node_modules:
        for name in ('room-zstd.mcap', 'room-lz4.mcap'):
            r = Report(name)
            check_equivalent(r, mcap_stream(os.path.join(HERE, name), args.node_modules, r),
                             header, scans, False)
            reports.append(r)
    else:
        print('MCAP files skipped (no --node-modules)')
    for r in reports:
        r.print()
    return 1 if any(r.failures for r in reports) else 0


if __name__ == '__main__':
    sys.exit(main())

# SPDX-License-Identifier: BSD-3-Clause
"""The ROS messages that stand for datasets/room/room.sglog, shared by the bag writers here.

Run with Debian's python3 (no ROS package is needed by this module itself):

    /usr/bin/python3 tests/data/bags/room/sglog_messages.py             # summary
    /usr/bin/python3 tests/data/bags/room/sglog_messages.py --json FILE # the records, for make_ros2.mjs

`records()` yields the messages of the "sglog-equivalent" bags in the order they are written, as
dicts {"topic", "type", "sec", "nsec", "fields"}: "type" is the ROS 1 name (sensor_msgs/Range; the
ROS 2 name puts "/msg/" in the middle), sec/nsec the log time (always the message's header stamp),
and "fields" the message as nested dicts named like the .msg fields. A header is
{"stamp": [sec, nsec], "frame_id": ...}; each writer adds the ROS 1 header.seq itself and
spells the stamp its way. A range of +inf (no echo) is the float inf here and "inf" in the JSON.

Conventions (README.md here explains them):
- stamp = 1700000000 s + the sglog time, converted from the decimal text with decimal.Decimal;
- every yaw becomes (0, 0, sin(t/2), cos(t/2)), z and w nudged by a few ulps until
  atan2(2(wz + xy), ww + xx - yy - zz) gives back the double t exactly;
- /tf_static once (sonar mounting poses), then per scan /odom, /ground_truth (if the scan has a
  true pose) and one /sonar Range per reading in file order, all stamped with the scan's time.
"""

import argparse
import json
import math
import os
import struct
import sys
from decimal import Decimal

HERE = os.path.dirname(os.path.abspath(__file__))
SGLOG = os.path.normpath(os.path.join(HERE, '..', '..', '..', '..', 'datasets', 'room', 'room.sglog'))
EPOCH = 1700000000  # seconds added to every sglog time
MAX_NUDGE = 64  # ulps (z and w together) tried before giving up on an angle
ROSARIA_MAX_RANGE = 5.0  # metres: where RosAria puts the point of a sonar without an echo


# ---- .sglog parsing (docs/formats.md, ".sglog — the native SonarGrid log, version 1") ----

def _fields(line):
    """The fields of one line, a comment (a field starting with '#') cut off."""
    out = []
    for f in line.split():
        if f.startswith('#'):
            break
        out.append(f)
    return out


def parse_sglog(path=SGLOG):
    """Header and scans of an .sglog, numbers kept as their text."""
    with open(path, encoding='utf-8-sig') as f:
        lines = f.read().split('\n')
    if _fields(lines[0]) != ['sglog', '1']:
        raise ValueError(f'{path}: not an sglog version 1 file')
    header = {'sonars': []}
    scans = []
    in_header = True
    ended = False
    for number, raw in enumerate(lines[1:], start=2):
        line = raw.rstrip('\r')
        if in_header and line.lstrip().startswith('name '):
            header['name'] = line.lstrip()[5:].strip()  # kept quoted; not used in the bags
            continue
        f = _fields(line)
        if not f:
            continue
        if ended:
            raise ValueError(f'{path}:{number}: record after end')
        key = f[0]
        if in_header:
            if key in ('robot', 'aperture', 'min_range', 'max_range') and len(f) == 2:
                header[key] = f[1]
            elif key == 'sonar' and len(f) == 5:
                if int(f[1]) != len(header['sonars']):
                    raise ValueError(f'{path}:{number}: sonar index out of order')
                header['sonars'].append({'x': f[2], 'y': f[3], 'theta': f[4]})
            elif key == 'streamed' and len(f) == 1:
                pass
            elif key == 'end_header' and len(f) == 1:
                in_header = False
            else:
                raise ValueError(f'{path}:{number}: unexpected header record {line!r}')
            continue
        if key == 'scan' and len(f) in (6, 8):
            truth = None if f[5] == 'none' and len(f) == 6 else f[5:8]
            if len(f) == 6 and f[5] != 'none':
                raise ValueError(f'{path}:{number}: bad scan line')
            scans.append({'time': f[1], 'pose': f[2:5], 'truth': truth, 'readings': [],
                          'line': number})
        elif key == 'r' and len(f) == 4:
            if not scans:
                raise ValueError(f'{path}:{number}: reading before the first scan')
            sonar = int(f[1])
            if sonar >= len(header['sonars']):
                raise ValueError(f'{path}:{number}: sonar {sonar} is not in the ring')
            scans[-1]['readings'].append({'sonar': sonar, 'range': f[2], 'time': f[3],
                                          'line': number})
        elif key == 'end' and len(f) == 1:
            ended = True
        else:
            raise ValueError(f'{path}:{number}: unexpected record {line!r}')
    if not ended:
        raise ValueError(f'{path}: truncated (no end line)')
    for key in ('robot', 'aperture', 'min_range', 'max_range'):
        if key not in header:
            raise ValueError(f'{path}: header lacks {key}')
    return header, scans


# ---- conversions ----

def stamp(text):
    """(sec, nsec) of EPOCH + the decimal time TEXT, computed exactly."""
    t = Decimal(text)
    whole = int(t.to_integral_value(rounding='ROUND_FLOOR'))
    frac = (t - whole) * 1000000000
    if frac != frac.to_integral_value():
        raise ValueError(f'time {text} is not a whole number of nanoseconds')
    nsec = int(frac)
    assert 0 <= nsec < 1000000000
    return EPOCH + whole, nsec


def yaw_back(z, w, x=0.0, y=0.0):
    """The yaw a reader computes from a quaternion: the formula the SonarGrid reader uses."""
    return math.atan2(2.0 * (w * z + x * y), w * w + x * x - y * y - z * z)


def _step(v, k):
    """V moved by K ulps (k < 0: down)."""
    toward = math.inf if k > 0 else -math.inf
    for _ in range(abs(k)):
        v = math.nextafter(v, toward)
    return v


def _ordinal(v):
    """Position of the double V on the number line, so that ulp distances are differences."""
    (i,) = struct.unpack('<q', struct.pack('<d', v))
    return i if i >= 0 else -(i & 0x7FFFFFFFFFFFFFFF)


def ulps_apart(a, b):
    return abs(_ordinal(a) - _ordinal(b))


def _nudges(limit):
    """(dz, dw) pairs, smallest total first; within one total z before w, down before up."""
    for total in range(limit + 1):
        for dz in sorted(range(-total, total + 1), key=lambda d: (abs(d), d)):
            rest = total - abs(dz)
            for dw in sorted({-rest, rest}):
                yield dz, dw


NUDGED = {}     # theta -> (ulps moved in z, in w), for every angle that needed a nudge
UNMATCHED = {}  # theta -> ulps between theta and yaw_back of the quaternion written instead
_QUAT_CACHE = {}


def yaw_quaternion(theta):
    """(x, y, z, w) of a rotation by THETA about z such that yaw_back gives THETA exactly.

    If no (z, w) within MAX_NUDGE ulps does (near +-pi/2 the formula's 1 - 2 z^2 cannot get
    small enough), the quaternion whose yaw_back is fewest ulps from THETA is returned, the least
    nudged of those, and THETA is listed in UNMATCHED."""
    key = repr(theta)  # keeps 0.0 and -0.0 apart
    if key in _QUAT_CACHE:
        return _QUAT_CACHE[key]
    z0 = math.sin(theta / 2.0)
    w0 = math.cos(theta / 2.0)
    best = None  # (ulps off, nudge index, dz, dw)
    for index, (dz, dw) in enumerate(_nudges(MAX_NUDGE)):
        off = ulps_apart(yaw_back(_step(z0, dz), _step(w0, dw)), theta)
        if best is None or off < best[0]:
            best = (off, index, dz, dw)
        if off == 0:
            break
    off, _, dz, dw = best
    if off:
        UNMATCHED[theta] = off
    elif dz or dw:
        NUDGED[theta] = (dz, dw)
    q = (0.0, 0.0, _step(z0, dz), _step(w0, dw))
    _QUAT_CACHE[key] = q
    return q


def quat_fields(theta_text):
    x, y, z, w = yaw_quaternion(float(theta_text))
    return {'x': x, 'y': y, 'z': z, 'w': w}


def _zero_cov():
    return [0.0] * 36


def _header(sec, nsec, frame):
    return {'stamp': [sec, nsec], 'frame_id': frame}


def odometry(sec, nsec, pose):
    x, y, theta = pose
    return {
        'header': _header(sec, nsec, 'odom'),
        'child_frame_id': 'base_link',
        'pose': {'pose': {'position': {'x': float(x), 'y': float(y), 'z': 0.0},
                          'orientation': quat_fields(theta)},
                 'covariance': _zero_cov()},
        'twist': {'twist': {'linear': {'x': 0.0, 'y': 0.0, 'z': 0.0},
                            'angular': {'x': 0.0, 'y': 0.0, 'z': 0.0}},
                  'covariance': _zero_cov()},
    }


def range_value(text):
    """A reading's range as a double: +inf for 'none' (REP 117: no echo)."""
    return math.inf if text == 'none' else float(text)


# ---- the records ----

def records(path=SGLOG):
    header, scans = parse_sglog(path)
    if not scans:
        return
    first = stamp(scans[0]['time'])
    transforms = []
    for i, s in enumerate(header['sonars']):
        transforms.append({
            'header': _header(first[0], first[1], 'base_link'),
            'child_frame_id': f'sonar_{i}',
            'transform': {'translation': {'x': float(s['x']), 'y': float(s['y']), 'z': 0.0},
                          'rotation': quat_fields(s['theta'])},
        })
    yield {'topic': '/tf_static', 'type': 'tf2_msgs/TFMessage', 'sec': first[0], 'nsec': first[1],
           'fields': {'transforms': transforms}}
    aperture = float(header['aperture'])
    min_range = float(header['min_range'])
    max_range = float(header['max_range'])
    for scan in scans:
        sec, nsec = stamp(scan['time'])
        yield {'topic': '/odom', 'type': 'nav_msgs/Odometry', 'sec': sec, 'nsec': nsec,
               'fields': odometry(sec, nsec, scan['pose'])}
        if scan['truth'] is not None:
            tx, ty, tt = scan['truth']
            yield {'topic': '/ground_truth', 'type': 'geometry_msgs/PoseStamped', 'sec': sec,
                   'nsec': nsec,
                   'fields': {'header': _header(sec, nsec, 'map'),
                              'pose': {'position': {'x': float(tx), 'y': float(ty), 'z': 0.0},
                                       'orientation': quat_fields(tt)}}}
        for r in scan['readings']:
            yield {'topic': '/sonar', 'type': 'sensor_msgs/Range', 'sec': sec, 'nsec': nsec,
                   'fields': {'header': _header(sec, nsec, f"sonar_{r['sonar']}"),
                              'radiation_type': 0,
                              'field_of_view': aperture,
                              'min_range': min_range,
                              'max_range': max_range,
                              'range': range_value(r['range'])}}


def rosaria_records(path=SGLOG):
    """The messages of a RosAria-style recording of the log, in the order written.

    Per scan: /RosAria/pose nav_msgs/Odometry (as /odom) and /RosAria/sonar
    sensor_msgs/PointCloud in frame base_link: one point per sonar, point i = sonar i's
    position + range * (cos, sin) of its heading, z 0; RosAria reports no echo as a point at
    the maximum range, 5 m. No /tf_static, no ground truth."""
    header, scans = parse_sglog(path)
    sonars = [(float(s['x']), float(s['y']), float(s['theta'])) for s in header['sonars']]
    for scan in scans:
        sec, nsec = stamp(scan['time'])
        yield {'topic': '/RosAria/pose', 'type': 'nav_msgs/Odometry', 'sec': sec, 'nsec': nsec,
               'fields': odometry(sec, nsec, scan['pose'])}
        ranges = {}
        for r in scan['readings']:
            if r['sonar'] in ranges:
                raise ValueError(f"line {r['line']}: sonar {r['sonar']} twice in one scan")
            ranges[r['sonar']] = ROSARIA_MAX_RANGE if r['range'] == 'none' else float(r['range'])
        if len(ranges) != len(sonars):
            raise ValueError(f"line {scan['line']}: a RosAria scan needs every sonar's reading")
        points = []
        for i, (x, y, theta) in enumerate(sonars):
            points.append({'x': x + ranges[i] * math.cos(theta),
                           'y': y + ranges[i] * math.sin(theta),
                           'z': 0.0})
        yield {'topic': '/RosAria/sonar', 'type': 'sensor_msgs/PointCloud', 'sec': sec,
               'nsec': nsec,
               'fields': {'header': _header(sec, nsec, 'base_link'), 'points': points,
                          'channels': []}}


def _jsonable(v):
    if isinstance(v, float) and math.isinf(v):
        return 'inf' if v > 0 else '-inf'
    if isinstance(v, dict):
        return {k: _jsonable(x) for k, x in v.items()}
    if isinstance(v, list):
        return [_jsonable(x) for x in v]
    return v


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--json', metavar='FILE', help='write the records as a JSON array')
    parser.add_argument('--sglog', default=SGLOG, help=argparse.SUPPRESS)
    args = parser.parse_args()
    recs = list(records(args.sglog))
    counts = {}
    for r in recs:
        counts[r['topic']] = counts.get(r['topic'], 0) + 1
    if args.json:
        with open(args.json, 'w', encoding='utf-8') as f:
            # Python writes each float in its shortest round-trip form, which JSON.parse reads
            # back to the same double.
            json.dump([_jsonable(r) for r in recs], f, allow_nan=False, separators=(',', ':'))
            f.write('\n')
    for topic, n in counts.items():
        print(f'{topic}: {n} messages', file=sys.stderr)
    report_angles(sys.stderr)


def report_angles(out):
    """Prints the angles that needed a nudge and those that could not be matched."""
    print(f'angles: {len(_QUAT_CACHE)} distinct, {len(NUDGED)} nudged, '
          f'{len(UNMATCHED)} not matched', file=out)
    for theta, (dz, dw) in sorted(NUDGED.items()):
        print(f'  nudged {theta!r}: z {dz:+d} ulp, w {dw:+d} ulp', file=out)
    for theta, off in sorted(UNMATCHED.items()):
        print(f'  NOT MATCHED {theta!r}: the closest quaternion gives a yaw {off} ulp off',
              file=out)


if __name__ == '__main__':
    main()

# SPDX-License-Identifier: MIT
"""Crafted frames for the tests: encoded with cantools from the DBC, E2E bytes set here."""
import os

from sbr_dashboard.dbc import DbcModel

DBC = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                   "dbc", "sbr.dbc")

IDS = dict(sign=0x300, status=0x301, det=0x310, obj=0x320)


def model():
    return DbcModel(DBC)


def frame(m, fid, counter, strict=True, **values):
    """Payload of message fid with the given physical values (others 0) and a valid E2E."""
    msg = m.messages[fid].message
    sig = {s.name: 0 for s in msg.signals}
    sig[m.messages[fid].counter_signal] = counter
    sig.update(values)
    data = bytearray(msg.encode(sig, scaling=True, strict=strict))
    return m.protect(fid, data)


class Sender:
    """Per-message alive counters, as the ECU keeps them."""

    def __init__(self, m):
        self.m = m
        self.counter = {fid: 0 for fid in m.messages}

    def __call__(self, fid, **values):
        c = self.counter[fid]
        self.counter[fid] = (c + 1) % 15
        return frame(self.m, fid, c, **values)

    def cycle(self, frame_counter, dets=(), signs=(), proc_ms=50.0, restr=None):
        """The frames of one image, in the ECU's order: signs, status, restrictions
        (limit, no overtaking, no overtaking for trucks, priority road, the limit's age;
        None: an ECU that sends none), detections, object."""
        out = []
        if signs:
            for slot, (cls, speed, conf, age) in enumerate(signs):
                out.append((0x300, self(0x300, SBR_Sign_Slot=slot, SBR_Sign_Class=cls,
                                        SBR_Sign_TrackId=slot, SBR_Sign_SpeedLimit=speed,
                                        SBR_Sign_Confidence=conf, SBR_Sign_AgeFrames=age,
                                        SBR_Sign_Count=len(signs))))
        else:
            out.append((0x300, self(0x300, SBR_Sign_Class=255, SBR_Sign_TrackId=255,
                                    SBR_Sign_SpeedLimit=255)))
        out.append((0x301, self(0x301, SBR_Status_FrameCounter=frame_counter,
                                SBR_Status_ProcessingTime=proc_ms,
                                SBR_Status_DetectionCount=len(dets))))
        if restr is not None:
            out.append((0x302, self(0x302, SBR_Restr_SpeedLimit=restr[0], SBR_Restr_NoOvertaking=restr[1],
                                    SBR_Restr_NoOvertakingTrucks=restr[2], SBR_Restr_PriorityRoad=restr[3],
                                    SBR_Restr_SpeedAge=restr[4])))
        for cls, conf, cx, cy in dets or ():
            out.append((0x310, self(0x310, SBR_Det_Class=cls, SBR_Det_Confidence=conf,
                                    SBR_Det_CenterX=cx, SBR_Det_CenterY=cy, SBR_Det_Width=40,
                                    SBR_Det_Height=40, SBR_Det_TrackId=63)))
        if not dets:
            out.append((0x310, self(0x310, SBR_Det_Class=63, SBR_Det_TrackId=63)))
        out.append((0x320, self(0x320, SBR_Obj_TrackId=255)))
        return out

#!/usr/bin/env python3
"""A test node offering std_srvs services: /switch (SetBool), /ping (Trigger), /reset (Empty)."""

import rospy
from std_srvs.srv import Empty, SetBool, SetBoolResponse, Trigger, TriggerResponse

state = {"on": False, "resets": 0}


def on_switch(request):
    state["on"] = request.data
    return SetBoolResponse(success=True, message="on" if request.data else "off")


def on_reset(request):
    state["resets"] += 1


rospy.init_node("switch_server")
rospy.Service("switch", SetBool, on_switch)
rospy.Service("ping", Trigger, lambda request: TriggerResponse(True, f"pong {state['resets']}"))
rospy.Service("reset", Empty, on_reset)
rospy.spin()

# SPDX-License-Identifier: BSD-3-Clause
"""pvbatch test: each default_values of the plugin's server-manager XML is the C++ default.

    pvbatch TestXMLDefaults.py <plugin.so> <CascadedShadowsView.xml>

The XML cannot ask the passes for their defaults, so it repeats them; this test keeps the two
equal. For every proxy of the XML with a VTK class (the baker, the shadow pass, the view) and
every property of it that calls a setter "SetX" with default_values, it reads "GetX" of a newly
constructed object of that class: through the client-server wrappers, with a probe proxy of
the same class that has one information-only property per getter (ParaView's way of reading a
getter). Doubles must agree to 1e-12 (relative). A getter the wrappers do not know fails too.
Exit status 0 on success; every failure prints one line starting with "FAIL".
"""
import sys
import xml.etree.ElementTree as ElementTree

from paraview import servermanager
from paraview.simple import LoadPlugin

plugin, xml_path = sys.argv[1], sys.argv[2]
failures = []


def fail(message):
    print("FAIL: " + message)
    failures.append(message)


LoadPlugin(plugin, remote=False, ns=globals())

# The properties with a default and a setter, per VTK class of the XML.
KINDS = {"IntVectorProperty": ("Int", int), "DoubleVectorProperty": ("Double", float)}
checked = {}  # class -> [(proxy, property, kind, getter, defaults)]
for group in ElementTree.parse(xml_path).getroot().iter("ProxyGroup"):
    for proxy in group:
        vtk_class = proxy.get("class")
        if not vtk_class:
            continue
        for prop in proxy:
            command, defaults = prop.get("command"), prop.get("default_values")
            if prop.get("information_only") == "1" or not command or defaults is None:
                continue
            if prop.tag not in KINDS:
                fail("%s.%s: a %s is not checked; add its kind to this test"
                     % (proxy.get("name"), prop.get("name"), prop.tag))
                continue
            if not command.startswith("Set"):
                fail("%s.%s calls %s, not a setter SetX with a getter GetX"
                     % (proxy.get("name"), prop.get("name"), command))
                continue
            checked.setdefault(vtk_class, []).append(
                (proxy.get("name"), prop.get("name"), prop.tag, "Get" + command[3:],
                 [KINDS[prop.tag][1](v) for v in defaults.split()]))

if not checked:
    fail("no property with a default in %s" % xml_path)

# A value no getter returns: still there after the pull, the getter was not reached.
SENTINEL = "-987654"

# One probe proxy per class: information-only properties call the getters of a new object.
probes = ['<ServerManagerConfiguration><ProxyGroup name="csm_default_probes">']
for vtk_class, props in sorted(checked.items()):
    probes.append('<Proxy name="%s" class="%s">' % (vtk_class, vtk_class))
    for proxy_name, name, tag, getter, defaults in props:
        kind = KINDS[tag][0]
        probes.append('<%s name="%s" command="%s" number_of_elements="%d" default_values="%s" '
                      'information_only="1"><Simple%sInformationHelper /></%s>'
                      % (tag, getter, getter, len(defaults), " ".join([SENTINEL] * len(defaults)),
                         kind, tag))
    probes.append("</Proxy>")
probes.append("</ProxyGroup></ServerManagerConfiguration>")
pxm = servermanager.vtkSMProxyManager.GetProxyManager().GetActiveSessionProxyManager()
if not pxm.LoadConfigurationXML("".join(probes)):
    fail("the probe proxies were not accepted")

count = 0
for vtk_class, props in sorted(checked.items()):
    probe = pxm.NewProxy("csm_default_probes", vtk_class)
    if probe is None:
        fail("cannot create a %s" % vtk_class)
        continue
    probe.UpdatePropertyInformation()
    for proxy_name, name, tag, getter, defaults in props:
        info = probe.GetProperty(getter)
        values = [info.GetElement(i) for i in range(info.GetNumberOfElements())]
        if any(v == float(SENTINEL) for v in values):
            fail("%s::%s() was not called (not wrapped?)" % (vtk_class, getter))
            continue
        if tag == "DoubleVectorProperty":
            same = len(values) == len(defaults) and all(
                abs(a - b) <= 1e-12 * max(1.0, abs(b)) for a, b in zip(values, defaults))
        else:
            same = values == defaults
        count += 1
        print("%s.%s: XML default %s, %s::%s() %s%s"
              % (proxy_name, name, defaults, vtk_class, getter, values, "" if same else "  <--"))
        if not same:
            fail("%s.%s: the XML's default_values %s differ from %s::%s() = %s"
                 % (proxy_name, name, defaults, vtk_class, getter, values))
    probe.UnRegister(None)

if failures:
    print("FAIL: %d check(s) failed" % len(failures))
    sys.exit(1)
print("PASS: %d defaults of %s equal their getters" % (count, xml_path))

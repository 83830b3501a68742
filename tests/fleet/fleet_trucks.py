"""The fleet's trucks: each one of a shipped vehicle file's type, drawn from that file's spreads.

What a truck is (the scenario's scales, which the simulator applies to the type's vehicle file):
its cargo (load_scale, the file's mass_sigma_kg), its drag area (cda_scale, cda_sigma_m2), its
tires' rolling resistance against the pavement's own (tire_crr_scale, tire_crr_sigma) and its
engine's friction (engine_friction_scale, friction_sigma). Each draw is cut at two sigmas, as a
fleet manager would send a truck three sigmas off its type to the workshop.

What the analysis is told: the type's vehicle file with the truck's own VIN (vehicles/<id>.toml),
and the type's mass (the recording declares it: the mass-error effect takes the cargo back out of
meta.toml), as a fleet that knows its trucks by type and VIN.
"""
import re
import tomllib
from dataclasses import dataclass

TYPES = ("mnroad-truck", "tractor-53ft-18speed")
CUT_SIGMAS = 2.0

# VIN transliteration and position weights, ISO 3779 / 49 CFR 565 (the North American check digit).
VIN_LETTERS = {**{c: i + 1 for i, c in enumerate("ABCDEFGH")}, **{c: i + 1 for i, c in enumerate("JKLMN")},
               "P": 7, "R": 9, **{c: i + 2 for i, c in enumerate("STUVWXYZ")}}
VIN_WEIGHTS = (8, 7, 6, 5, 4, 3, 2, 10, 0, 9, 8, 7, 6, 5, 4, 3, 2)


def vin_check_digit(vin):
    total = sum((int(c) if c.isdigit() else VIN_LETTERS[c]) * w for c, w in zip(vin, VIN_WEIGHTS))
    return "X" if total % 11 == 10 else str(total % 11)


def make_vin(index, kind):
    """A fleet VIN: a made-up manufacturer code (9FL), the type, model year 2024 (R), plant F and a
    serial per truck, with its check digit: 17 characters, unique by the serial."""
    body = f"9FL{'MN' if kind == TYPES[0] else 'TR'}X53" + "0" + "RF" + f"{index + 1:06d}"
    return body[:8] + vin_check_digit(body) + body[9:]


@dataclass
class Truck:
    id: str
    vin: str
    kind: str           # the vehicle file's name (config/vehicles/<kind>.toml)
    file: str           # its own file, relative to the fleet folder: the type's with its VIN
    nominal_mass_kg: float
    nominal_cda_m2: float
    load_scale: float
    cda_scale: float
    tire_crr_scale: float
    engine_friction_scale: float

    @property
    def scales(self):
        return {"load_scale": self.load_scale, "cda_scale": self.cda_scale, "tire_crr_scale": self.tire_crr_scale,
                "engine_friction_scale": self.engine_friction_scale}

    def row(self):
        return {"truck": self.id, "vin": self.vin, "type": self.kind, "type_file": f"config/vehicles/{self.kind}.toml",
                "vehicle_file": self.file, "mass_kg": round(self.nominal_mass_kg * self.load_scale, 1),
                "nominal_mass_kg": self.nominal_mass_kg, "load_scale": self.load_scale,
                "cda_m2": round(self.nominal_cda_m2 * self.cda_scale, 4), "nominal_cda_m2": self.nominal_cda_m2,
                "cda_scale": self.cda_scale, "tire_crr_scale": self.tire_crr_scale,
                "engine_friction_scale": self.engine_friction_scale}


def cut_normal(rng, sigma):
    """1 + a normal draw of this relative sigma, cut at CUT_SIGMAS, to 4 decimals."""
    while True:
        z = rng.standard_normal()
        if abs(z) <= CUT_SIGMAS:
            return round(1.0 + sigma * z, 4)


def with_vin(text, vin):
    """The vehicle file's text with this VIN: its own line replaced, or one added after the name's."""
    line = f'vin = "{vin}"  # the fleet truck\'s own (tests/fleet/make_fleet.py); every number is its type\'s'
    if re.search(r"^vin\s*=", text, flags=re.M):
        return re.sub(r"^vin\s*=.*$", line, text, count=1, flags=re.M)
    return re.sub(r"^(name\s*=.*)$", lambda m: m.group(1) + "\n" + line, text, count=1, flags=re.M)


def draw_trucks(config, out, count, rng):
    """count trucks, the types alternating; writes out/vehicles/<id>.toml."""
    folder = out / "vehicles"
    folder.mkdir(parents=True, exist_ok=True)
    trucks = []
    for i in range(count):
        kind = TYPES[i % len(TYPES)]
        text = (config / "vehicles" / f"{kind}.toml").read_text()
        v = tomllib.loads(text)
        body = v["body"]
        mass = sum(a["load_kg"] for a in v["axle"])
        if "tire_crr_sigma" not in body:
            raise SystemExit(f"config/vehicles/{kind}.toml: no body.tire_crr_sigma, the tires' spread the fleet draws from")
        truck = Truck(id=f"T{i + 1:02d}", vin=make_vin(i, kind), kind=kind, file=f"vehicles/T{i + 1:02d}.toml",
                      nominal_mass_kg=mass, nominal_cda_m2=body["cda_m2"],
                      load_scale=cut_normal(rng, body["mass_sigma_kg"] / mass),
                      cda_scale=cut_normal(rng, body["cda_sigma_m2"] / body["cda_m2"]),
                      tire_crr_scale=cut_normal(rng, body["tire_crr_sigma"]),
                      engine_friction_scale=cut_normal(rng, v["engine"]["friction_sigma"]))
        (out / truck.file).write_text(with_vin(text, truck.vin))
        trucks.append(truck)
    return trucks

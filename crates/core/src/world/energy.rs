//! Rotary-wing propulsion power of Zeng, Xu and Zhang (doi:10.1109/TWC.2019.2902559; IEEE Trans. Wireless Commun. 18(4),
//! 2019, Eq. 12), used for the battery constraint:
//!
//! P(V) = P0 (1 + 3 V^2 / U_tip^2) + Pi (sqrt(1 + V^4 / (4 v0^4)) - V^2 / (2 v0^2))^(1/2)
//!        + 0.5 d0 rho s A V^3,
//! P0 = (delta / 8) rho s A Omega^3 R^3, Pi = (1 + k) W^(3/2) / sqrt(2 rho A),
//! v0 = sqrt(W / (2 rho A)).
//!
//! Energy of a path flown at constant speed V: P(V) L / V (level flight) + m g per metre
//! climbed (descents recover nothing) + a turning cost per radian of heading change.
//! W is the airframe weight plus the payload, so payload costs energy.

use serde::{Deserialize, Serialize};

/// Standard gravity, m/s^2.
pub const G: f64 = 9.806_65;

/// Parameters of the rotary-wing power model (defaults: Zeng, Xu, Zhang 2019, Table I).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RotaryWing {
    /// Airframe weight W without payload, newtons (20 N).
    pub weight_n: f64,
    /// Air density rho, kg/m^3 (1.225).
    pub air_density: f64,
    /// Rotor radius R, m (0.4).
    pub rotor_radius: f64,
    /// Rotor disc area A, m^2 (0.503).
    pub disc_area: f64,
    /// Blade angular velocity Omega, rad/s (300).
    pub blade_angular_velocity: f64,
    /// Tip speed U_tip, m/s (120).
    pub tip_speed: f64,
    /// Rotor solidity s (0.05).
    pub solidity: f64,
    /// Fuselage drag ratio d0 (0.6).
    pub fuselage_drag_ratio: f64,
    /// Incremental correction factor to induced power k (0.1).
    pub induced_correction: f64,
    /// Profile drag coefficient delta (0.012).
    pub profile_drag: f64,
    /// Energy per radian of heading change, J/rad (documented choice: 50 J/rad, i.e. a
    /// 90-degree turn costs about what 8.5 m of cruise flight does).
    pub turn_energy_per_rad: f64,
}

impl Default for RotaryWing {
    fn default() -> Self {
        Self {
            weight_n: 20.0,
            air_density: 1.225,
            rotor_radius: 0.4,
            disc_area: 0.503,
            blade_angular_velocity: 300.0,
            tip_speed: 120.0,
            solidity: 0.05,
            fuselage_drag_ratio: 0.6,
            induced_correction: 0.1,
            profile_drag: 0.012,
            turn_energy_per_rad: 50.0,
        }
    }
}

impl RotaryWing {
    /// Blade profile power in hover, P0 (W).
    #[must_use]
    pub fn blade_profile_power(&self) -> f64 {
        self.profile_drag / 8.0
            * self.air_density
            * self.solidity
            * self.disc_area
            * self.blade_angular_velocity.powi(3)
            * self.rotor_radius.powi(3)
    }

    /// Induced power in hover, Pi (W), for total weight `w` (N).
    #[must_use]
    pub fn induced_power(&self, w: f64) -> f64 {
        (1.0 + self.induced_correction) * w.powf(1.5)
            / (2.0 * self.air_density * self.disc_area).sqrt()
    }

    /// Mean rotor induced velocity in hover, v0 (m/s), for total weight `w` (N).
    #[must_use]
    pub fn hover_induced_velocity(&self, w: f64) -> f64 {
        (w / (2.0 * self.air_density * self.disc_area)).sqrt()
    }

    /// Propulsion power at horizontal speed `v` (m/s) carrying `payload_kg`, watts.
    #[must_use]
    pub fn power(&self, v: f64, payload_kg: f64) -> f64 {
        let w = self.weight_n + payload_kg * G;
        let p0 = self.blade_profile_power();
        let pi = self.induced_power(w);
        let v0 = self.hover_induced_velocity(w);
        let v2 = v * v;
        let blade = p0 * (1.0 + 3.0 * v2 / (self.tip_speed * self.tip_speed));
        let r = v2 / (2.0 * v0 * v0);
        let induced = pi * ((1.0 + r * r).sqrt() - r).max(0.0).sqrt();
        let parasite = 0.5
            * self.fuselage_drag_ratio
            * self.air_density
            * self.solidity
            * self.disc_area
            * v2
            * v;
        blade + induced + parasite
    }

    /// Mass of the aircraft with payload, kg.
    #[must_use]
    pub fn mass(&self, payload_kg: f64) -> f64 {
        self.weight_n / G + payload_kg
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Figures of Zeng, Xu, Zhang (2019) quoted in ALGORITHMS.md.
    #[test]
    fn reproduces_published_power_figures() {
        let m = RotaryWing::default();
        assert!((m.blade_profile_power() - 79.86).abs() < 0.01);
        assert!((m.induced_power(20.0) - 88.63).abs() < 0.01);
        assert!((m.hover_induced_velocity(20.0) - 4.03).abs() < 0.01);
        assert!((m.power(0.0, 0.0) - 168.5).abs() < 0.05);
        for (v, p) in [
            (5.0, 143.6),
            (10.0, 126.0),
            (15.0, 138.5),
            (20.0, 178.3),
            (25.0, 249.0),
        ] {
            assert!(
                (m.power(v, 0.0) - p).abs() < 0.1,
                "P({v}) = {}",
                m.power(v, 0.0)
            );
        }
        assert!((m.power(15.0, 0.0) / 15.0 - 9.24).abs() < 0.01);
    }

    #[test]
    fn payload_costs_power() {
        let m = RotaryWing::default();
        assert!(m.power(15.0, 1.0) > m.power(15.0, 0.0));
    }
}

(define (domain solar-rover)
  (:requirements :typing :fluents :time :negative-preconditions)
  (:types waypoint)
  (:predicates (at ?w - waypoint) (road ?a - waypoint ?b - waypoint) (parked)
               (driving ?a - waypoint ?b - waypoint) (charging) (target ?w - waypoint)
               (imaged ?w - waypoint) (sent ?w - waypoint)
               (mission) (morning) (afternoon) (night) (stranded))
  (:functions (battery) (capacity) (sun) (sun-rate) (clock) (noon) (charge-eff)
              (dist ?a - waypoint ?b - waypoint) (progress) (speed) (drive-power)
              (image-cost) (send-cost))
  (:process mission-clock
    :parameters ()
    :precondition (and (mission))
    :effect (and (increase (clock) (* #t 1))))
  (:process sun-rises
    :parameters ()
    :precondition (and (morning))
    :effect (and (increase (sun) (* #t (sun-rate)))))
  (:process sun-sets
    :parameters ()
    :precondition (and (afternoon))
    :effect (and (decrease (sun) (* #t (sun-rate)))))
  (:event noon-passes
    :parameters ()
    :precondition (and (morning) (>= (clock) (noon)))
    :effect (and (not (morning)) (afternoon)))
  (:event dusk
    :parameters ()
    :precondition (and (afternoon) (<= (sun) 0))
    :effect (and (not (afternoon)) (night)))
  ;; the panels turn sunlight into charge: a rate that itself changes in time
  (:process charge
    :parameters ()
    :precondition (and (charging))
    :effect (and (increase (battery) (* #t (* (charge-eff) (sun))))))
  (:event battery-full
    :parameters ()
    :precondition (and (charging) (>= (battery) (capacity)))
    :effect (and (not (charging))))
  (:process drive
    :parameters (?a - waypoint ?b - waypoint)
    :precondition (and (driving ?a ?b))
    :effect (and (increase (progress) (* #t (speed))) (decrease (battery) (* #t (drive-power)))))
  (:event battery-dead
    :parameters (?a - waypoint ?b - waypoint)
    :precondition (and (driving ?a ?b) (<= (battery) 0))
    :effect (and (not (driving ?a ?b)) (stranded)))
  (:action deploy-panels
    :parameters ()
    :precondition (and (parked) (not (charging)) (not (night)) (< (battery) (capacity)))
    :effect (and (charging)))
  (:action stow-panels
    :parameters ()
    :precondition (and (charging))
    :effect (and (not (charging))))
  (:action depart
    :parameters (?a - waypoint ?b - waypoint)
    :precondition (and (at ?a) (road ?a ?b) (parked) (not (charging)) (> (battery) 0))
    :effect (and (not (at ?a)) (not (parked)) (driving ?a ?b) (assign (progress) 0)))
  (:action arrive
    :parameters (?a - waypoint ?b - waypoint)
    :precondition (and (driving ?a ?b) (>= (progress) (dist ?a ?b)))
    :effect (and (not (driving ?a ?b)) (at ?b) (parked)))
  (:action take-image
    :parameters (?w - waypoint)
    :precondition (and (at ?w) (parked) (target ?w) (not (imaged ?w))
                       (>= (battery) (image-cost)))
    :effect (and (imaged ?w) (decrease (battery) (image-cost))))
  (:action transmit
    :parameters (?w - waypoint)
    :precondition (and (imaged ?w) (parked) (not (sent ?w)) (not (night))
                       (>= (battery) (send-cost)))
    :effect (and (sent ?w) (decrease (battery) (send-cost))))
)
